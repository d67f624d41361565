# The package's layout, the same in every space it runs from: programs (nodes and tools) in
# lib/multirobot_audio/, shipped data in share/multirobot_audio/. Programs find the data at run
# time from their own place (package_data/), so nothing compiled in points at the source tree;
# the build tree (and the catkin devel space) get a share/multirobot_audio/ of links to the
# source tree's data, an install space a copy.
set(MULTIROBOT_AUDIO_PROGRAM_DESTINATION lib/multirobot_audio)
set(MULTIROBOT_AUDIO_DATA_DESTINATION share/multirobot_audio)

# NAME=SOURCE: what share/multirobot_audio/NAME holds, from the source tree's SOURCE.
set(MULTIROBOT_AUDIO_DATA
  package.xml=package.xml
  launch=launch
  maps=maps
  rviz=rviz
  tables=audio_propagation/tables
  make_speech.sh=nava_modem/tools/make_speech.sh)

# Makes SHARE_DIR a share folder of links to the source tree's data (at configure time).
function(multirobot_audio_link_data share_dir)
  file(MAKE_DIRECTORY ${share_dir})
  foreach(entry ${MULTIROBOT_AUDIO_DATA})
    string(REPLACE "=" ";" pair ${entry})
    list(GET pair 0 name)
    list(GET pair 1 source)
    file(REMOVE ${share_dir}/${name})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${source} ${share_dir}/${name} SYMBOLIC)
  endforeach()
endfunction()

multirobot_audio_link_data(${CMAKE_BINARY_DIR}/share/multirobot_audio)

# Installs the programs (nodes and tools) as lib/multirobot_audio/NAME, where rosrun finds them.
function(multirobot_audio_install_programs)
  install(TARGETS ${ARGN} RUNTIME DESTINATION ${MULTIROBOT_AUDIO_PROGRAM_DESTINATION})
endfunction()

foreach(entry ${MULTIROBOT_AUDIO_DATA})
  string(REPLACE "=" ";" pair ${entry})
  list(GET pair 0 name)
  list(GET pair 1 source)
  if(IS_DIRECTORY ${PROJECT_SOURCE_DIR}/${source})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${source}/ DESTINATION ${MULTIROBOT_AUDIO_DATA_DESTINATION}/${name})
  elseif(source MATCHES "\\.sh$")
    install(PROGRAMS ${PROJECT_SOURCE_DIR}/${source} DESTINATION ${MULTIROBOT_AUDIO_DATA_DESTINATION})
  else()
    install(FILES ${PROJECT_SOURCE_DIR}/${source} DESTINATION ${MULTIROBOT_AUDIO_DATA_DESTINATION})
  endif()
endforeach()

# A standalone build (this package at the top, not in a catkin workspace, whose catkin installs
# its own setup files) installs a setup.bash beside lib/ and share/.
if(CMAKE_SOURCE_DIR STREQUAL PROJECT_SOURCE_DIR)
  install(FILES ${PROJECT_SOURCE_DIR}/cmake/install_setup.bash DESTINATION . RENAME setup.bash)
endif()
