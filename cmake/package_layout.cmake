# The package's layout, the same in every space it runs from: programs (nodes and tools) in
# lib/multirobot_audio/, shipped data in share/multirobot_audio/. Programs find the data at run
# time from their own place (package_data/), so nothing compiled in points at the source tree;
# the build tree (and the catkin devel space) get a share/multirobot_audio/ of links to the
# source tree's run-time data, an install space a copy of all of it.
set(MULTIROBOT_AUDIO_PROGRAM_DESTINATION lib/multirobot_audio)
set(MULTIROBOT_AUDIO_DATA_DESTINATION share/multirobot_audio)

# NAME=SOURCE: what share/multirobot_audio/NAME holds, from the source tree's SOURCE. The first
# list is what the programs read at run time: linked into the build tree's and the devel space's
# share folders too. The launch files and rviz configs are only installed: links to them inside
# the package's folder would make roslaunch find each launch file several times.
set(MULTIROBOT_AUDIO_RUN_TIME_DATA
  package.xml=package.xml
  maps=maps
  tables=audio_propagation/tables
  make_speech.sh=nava_modem/tools/make_speech.sh)
set(MULTIROBOT_AUDIO_DATA ${MULTIROBOT_AUDIO_RUN_TIME_DATA}
  launch=launch
  rviz=rviz)

# Makes SHARE_DIR a share folder of links to the source tree's run-time data (at configure time).
function(multirobot_audio_link_data share_dir)
  file(MAKE_DIRECTORY ${share_dir})
  foreach(entry ${MULTIROBOT_AUDIO_RUN_TIME_DATA})
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
