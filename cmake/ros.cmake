# The ROS side: messages, nodes (all in src/), rostests and launch-file checks (in test/).

add_message_files(DIRECTORY msg FILES
  AudioPacket.msg
  AudioReception.msg
  CarrierSense.msg
  Fiducial.msg
  FiducialArray.msg
  Job.msg
  LockState.msg
  ChargingState.msg
  LockstepHello.msg
  LockstepOrder.msg
  LockstepAck.msg
  RobotPoses.msg
  RobotScans.msg
  RobotCommands.msg
  PacketTiming.msg
  Teammate.msg
  Teammates.msg
)
add_action_files(DIRECTORY action FILES AcquireLock.action)
generate_messages(DEPENDENCIES std_msgs geometry_msgs sensor_msgs actionlib_msgs)

catkin_package(CATKIN_DEPENDS message_runtime roscpp std_msgs geometry_msgs sensor_msgs nav_msgs
               visualization_msgs rosgraph_msgs tf2_msgs diagnostic_msgs actionlib actionlib_msgs std_srvs)

# Bridges between the components and ROS: conversions and the node classes.
add_library(multirobot_audio_ros STATIC
  src/conversions.cpp
  src/rviz_markers.cpp
  src/input_checks.cpp
  src/input_guard.cpp
  src/subscription_stats.cpp
  src/params.cpp
  src/lockstep_participant.cpp
  src/world_sim_ros.cpp
  src/wanderer_ros.cpp
  src/wanderer_team_ros.cpp
  src/audio_propagation_ros.cpp
  src/nava_modem_options.cpp
  src/nava_modem_ros.cpp
  src/ranging_ros.cpp
  src/simulated_ranging_ros.cpp
  src/local_mutex_ros.cpp
  src/mutex_client_ros.cpp
)
target_include_directories(multirobot_audio_ros PUBLIC ${PROJECT_SOURCE_DIR}/src)
target_include_directories(multirobot_audio_ros SYSTEM PUBLIC ${catkin_INCLUDE_DIRS})
target_link_libraries(multirobot_audio_ros PUBLIC audio_propagation nava_modem ranging local_mutex world_sim behaviours grid
                      ${catkin_LIBRARIES})
add_dependencies(multirobot_audio_ros ${PROJECT_NAME}_generate_messages_cpp)
# The local-map navigation's bridges (its ~params, range and map conversions), for every node
# that drives with local_navigation.
add_library(navigation_ros STATIC src/navigation_conversions.cpp src/navigation_params.cpp)
target_link_libraries(navigation_ros PUBLIC multirobot_audio_ros local_navigation)
# The Sounds Good team's bridges, apart so that only their nodes link the explorer.
add_library(sounds_good_ros STATIC src/sounds_good_explorer_ros.cpp src/task_monitor_ros.cpp)
target_link_libraries(sounds_good_ros PUBLIC navigation_ros sounds_good_explorer)
# The charging robots' bridges, apart so that only their nodes link the charging demo.
add_library(charging_ros STATIC src/charging_conversions.cpp src/charging_lock.cpp src/charging_state_publisher.cpp
            src/charging_demo_ros.cpp)
target_link_libraries(charging_ros PUBLIC navigation_ros charging_demo)

# Node executables keep their ROS names (rosrun multirobot_audio world_sim).
function(multirobot_audio_node target name source)
  add_executable(${target} ${source})
  set_target_properties(${target} PROPERTIES OUTPUT_NAME ${name})
  target_link_libraries(${target} multirobot_audio_ros)
  multirobot_audio_install_programs(${target})
endfunction()
multirobot_audio_node(world_sim_node world_sim src/world_sim_node.cpp)
multirobot_audio_node(wanderer_node wanderer src/wanderer_node.cpp)
multirobot_audio_node(audio_propagation_node audio_propagation src/audio_propagation_node.cpp)
multirobot_audio_node(nava_modem_node nava_modem src/nava_modem_node.cpp)
multirobot_audio_node(local_mutex_node local_mutex src/local_mutex_node.cpp)
multirobot_audio_node(mutex_client_node mutex_client src/mutex_client_node.cpp)
multirobot_audio_node(sounds_good_explorer_node sounds_good_explorer src/sounds_good_explorer_node.cpp)
multirobot_audio_node(task_monitor_node task_monitor src/task_monitor_node.cpp)
target_link_libraries(sounds_good_explorer_node sounds_good_ros)
target_link_libraries(task_monitor_node sounds_good_ros)
multirobot_audio_node(charging_demo_node charging_demo src/charging_demo_node.cpp)
target_link_libraries(charging_demo_node charging_ros)

# The nodes in the devel space find the package's data as the tools in the build tree do
# (package_layout.cmake).
multirobot_audio_link_data(${CATKIN_DEVEL_PREFIX}/share/multirobot_audio)

if(MULTIROBOT_AUDIO_TESTS)
  find_package(rostest REQUIRED)
  find_package(roslaunch REQUIRED)

  catkin_add_gtest(conversions_test test/conversions_test.cpp test/ranging_conversions_test.cpp)
  target_link_libraries(conversions_test multirobot_audio_ros)
  catkin_add_gtest(input_checks_test test/input_checks_test.cpp)
  target_link_libraries(input_checks_test multirobot_audio_ros)
  catkin_add_gtest(sounds_good_conversions_test test/sounds_good_conversions_test.cpp)
  target_link_libraries(sounds_good_conversions_test sounds_good_ros)
  catkin_add_gtest(charging_conversions_test test/charging_conversions_test.cpp)
  target_link_libraries(charging_conversions_test charging_ros)

  # The package installed into a temporary prefix and run from there with the source tree hidden
  # (test/install_test.sh): the nodes, every tool, the tables, launch files, maps and messages.
  add_test(NAME install_space COMMAND ${PROJECT_SOURCE_DIR}/test/install_test.sh ${PROJECT_SOURCE_DIR} ${CMAKE_BINARY_DIR})
  add_dependencies(tests world_sim_node wanderer_node audio_propagation_node nava_modem_node local_mutex_node
                   mutex_client_node sounds_good_explorer_node task_monitor_node charging_demo_node nava_encode
                   nava_decode nava_room nava_bench audio_propagation_query audio_propagation_bench audio_scene_render
                   audio_channel_validate decode_table_bench world_sim_bench local_mutex_sim sounds_good_experiment
                   charging_experiment)

  add_rostest_gtest(world_sim_rostest test/world_sim.test test/world_sim_rostest.cpp test/rostest_main.cpp)
  target_link_libraries(world_sim_rostest multirobot_audio_ros)
  add_dependencies(world_sim_rostest world_sim_node)

  add_rostest_gtest(lockstep_rostest test/lockstep.test test/lockstep_rostest.cpp)
  target_link_libraries(lockstep_rostest multirobot_audio_ros)
  add_dependencies(lockstep_rostest world_sim_node wanderer_node)
  # Two lockstep runs of the same team and seed: the same summary and the same audio traffic.
  add_test(NAME lockstep_reproducible COMMAND ${PROJECT_SOURCE_DIR}/test/lockstep_repro.sh 3 30)
  # audio_propagation resting through what it can foresee gives the same run as working every
  # step: the same world_sim summary and the same bag, on a busy team of 20.
  add_test(NAME lockstep_update_modes COMMAND ${PROJECT_SOURCE_DIR}/test/lockstep_repro.sh 20 20
           world:=${PROJECT_SOURCE_DIR}/maps/office_team20_world.yaml -- update:=every_step -- update:=events)
  # A team driven by one process (the wanderer's ~robots, on world_sim's team topics) gives the
  # same run as a wanderer per robot.
  add_test(NAME lockstep_one_process COMMAND ${PROJECT_SOURCE_DIR}/test/lockstep_repro.sh 20 20
           world:=${PROJECT_SOURCE_DIR}/maps/office_team20_world.yaml -- one_process:=false -- one_process:=true)
  # The lockstep bench runs and prints its figures (no timing is asserted).
  add_test(NAME lockstep_bench_quick COMMAND ${PROJECT_SOURCE_DIR}/scripts/lockstep_bench.sh 20 5)
  set_tests_properties(lockstep_bench_quick PROPERTIES PASS_REGULAR_EXPRESSION "real_time_factor [0-9.]+")
  add_dependencies(tests world_sim_node wanderer_node audio_propagation_node)

  # scripts/soak.sh's short forms: its arguments, a soak of 3 simulated minutes of the charging
  # demo in lockstep that passes, and one with a controller killed half way that must fail; and
  # its judge on made-up runs (flat robots, growth, deaths, short runs).
  add_test(NAME soak_args COMMAND ${PROJECT_SOURCE_DIR}/test/soak_test.sh args)
  add_test(NAME soak_report COMMAND ${PROJECT_SOURCE_DIR}/test/soak_report_test.sh)
  add_test(NAME soak_short COMMAND ${PROJECT_SOURCE_DIR}/test/soak_test.sh pass)
  add_test(NAME soak_node_died COMMAND ${PROJECT_SOURCE_DIR}/test/soak_test.sh died)
  add_dependencies(tests world_sim_node audio_propagation_node local_mutex_node charging_demo_node)

  add_rostest_gtest(record_rostest test/record.test test/record_rostest.cpp)
  target_link_libraries(record_rostest multirobot_audio_ros ${rosbag_LIBRARIES})
  add_dependencies(record_rostest world_sim_node)

  add_rostest_gtest(audio_propagation_rostest test/audio_propagation.test test/audio_propagation_rostest.cpp
                  test/rostest_main.cpp)
  target_link_libraries(audio_propagation_rostest ${catkin_LIBRARIES})
  add_dependencies(audio_propagation_rostest world_sim_node audio_propagation_node)
  add_rostest(test/audio_propagation_map_topic.test DEPENDENCIES audio_propagation_rostest)
  # The same on the room profile at rate 1: a 64-byte frame through audio/tx.
  add_rostest(test/audio_propagation_frames.test DEPENDENCIES audio_propagation_rostest)
  # On the acoustic channel in the office's coupled rooms: ~rooms.
  add_rostest(test/audio_propagation_rooms.test DEPENDENCIES audio_propagation_rostest)
  add_rostest_gtest(sim_ranging_rostest test/sim_ranging.test test/sim_ranging_rostest.cpp test/rostest_main.cpp)
  target_link_libraries(sim_ranging_rostest ${catkin_LIBRARIES})
  add_dependencies(sim_ranging_rostest world_sim_node audio_propagation_node)

  # A broken peer against every simulated node: garbage, floods, a robot missing from TF.
  add_rostest_gtest(hostile_input_rostest test/hostile_input.test test/hostile_input_rostest.cpp test/hostile_peer.cpp)
  target_include_directories(hostile_input_rostest PRIVATE ${PROJECT_SOURCE_DIR}/test)
  target_link_libraries(hostile_input_rostest multirobot_audio_ros)
  add_dependencies(hostile_input_rostest world_sim_node audio_propagation_node wanderer_node sounds_good_explorer_node
                   local_mutex_node mutex_client_node charging_demo_node task_monitor_node)

  # Three local mutexes on the simulated audio channel; the test node plays their clients.
  add_rostest_gtest(local_mutex_rostest test/local_mutex.test test/local_mutex_rostest.cpp test/lock_watch.cpp
                    test/rostest_main.cpp)
  target_link_libraries(local_mutex_rostest multirobot_audio_ros)
  add_dependencies(local_mutex_rostest world_sim_node audio_propagation_node local_mutex_node)

  # A small Sounds Good team in the test room at high speed: jobs, local maps and plans.
  add_rostest_gtest(sounds_good_rostest test/sounds_good.test test/sounds_good_rostest.cpp test/rostest_main.cpp)
  target_link_libraries(sounds_good_rostest multirobot_audio_ros)
  add_dependencies(sounds_good_rostest world_sim_node audio_propagation_node sounds_good_explorer_node
                   task_monitor_node)

  # Three charging robots share one charger in the test room at 10x: each docks in turn.
  add_rostest_gtest(charging_demo_rostest test/charging_demo.test test/charging_demo_rostest.cpp test/lock_watch.cpp
                    test/rostest_main.cpp)
  target_link_libraries(charging_demo_rostest multirobot_audio_ros)
  add_dependencies(charging_demo_rostest world_sim_node audio_propagation_node local_mutex_node charging_demo_node)

  # A test run by test/nava_air.sh. Labelled "air": its links stream in real time with short
  # buffers, so scripts/test.sh runs these with nothing building beside them.
  function(multirobot_audio_air_add_test name test_file)
    add_test(NAME ${name} COMMAND ${PROJECT_SOURCE_DIR}/test/nava_air.sh ${test_file} ${ARGN})
    set_tests_properties(${name} PROPERTIES LABELS air)
  endfunction()
  # Over the air: built like rostest nodes, but each run by test/nava_air.sh, which starts the
  # PulseAudio server the test needs, runs the given .test file and stops the server.
  function(multirobot_audio_air_test target test_file)
    add_executable(${target} ${ARGN})
    target_include_directories(${target} PRIVATE ${PROJECT_SOURCE_DIR}/test)
    target_link_libraries(${target} multirobot_audio_ros GTest::gtest)
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/lib/${PROJECT_NAME})
    add_dependencies(${target} ${PROJECT_NAME}_generate_messages_cpp)
    add_dependencies(tests ${target} nava_modem_node)
    multirobot_audio_air_add_test(${target} ${test_file})
  endfunction()
  multirobot_audio_air_test(nava_air_rostest nava_air.test test/nava_air_rostest.cpp)
  # A broken peer against nava_modem's audio/tx over the air.
  multirobot_audio_air_test(hostile_nava_rostest hostile_nava.test test/hostile_nava_rostest.cpp test/hostile_peer.cpp)
  multirobot_audio_air_add_test(nava_air_room_rostest nava_air.test profile:=room)
  # 64-byte frames at each rate of the room profile's ladder.
  multirobot_audio_air_test(frames_air_rostest frames_air.test test/frames_air_rostest.cpp)
  # A stalled process and a sound server killed in the middle of a packet and restarted: every
  # packet is still heard exactly once.
  multirobot_audio_air_test(nava_air_faults_rostest nava_air_faults.test test/nava_air_faults_rostest.cpp)
  # Two-way ranging between three links on the air, and after the sound server restarts.
  multirobot_audio_air_test(ranging_air_rostest ranging_air.test test/ranging_air_rostest.cpp)
  multirobot_audio_air_add_test(ranging_air_nava_rostest ranging_air.test profile:=nava)
  multirobot_audio_air_test(mutex_air_rostest mutex_air.test test/mutex_air_rostest.cpp test/lock_watch.cpp
                            test/rostest_main.cpp)
  add_dependencies(tests local_mutex_node)
  # launch/team_robots.launch with every machine localhost: three robots' links on the air and
  # their controllers (the wanderers' announcements must cross the air), then the mutex task.
  multirobot_audio_air_test(team_robots_rostest team_robots.test test/team_robots_rostest.cpp)
  multirobot_audio_air_add_test(team_robots_mutex_rostest team_robots.test task:=mutex)
  add_dependencies(tests wanderer_node)
  # How roslaunch reads the team's machines, for remote hosts too: nothing is started.
  add_test(NAME team_robots_machines COMMAND /usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/team_robots_machines.py)

  foreach(launch_file sim_team.launch)
    roslaunch_add_file_check(launch/${launch_file} DEPENDENCIES world_sim_node wanderer_node audio_propagation_node)
  endforeach()
  roslaunch_add_file_check(launch/sim_team.launch one_process:=false
                           DEPENDENCIES world_sim_node wanderer_node audio_propagation_node)
  roslaunch_add_file_check(launch/include/wanderers.launch count:=2 DEPENDENCIES wanderer_node)
  roslaunch_add_file_check(launch/nava_robot.launch DEPENDENCIES nava_modem_node)
  roslaunch_add_file_check(launch/mutex_sim.launch
                           DEPENDENCIES world_sim_node audio_propagation_node local_mutex_node mutex_client_node)
  roslaunch_add_file_check(launch/mutex_robot.launch robot_id:=11
                           DEPENDENCIES nava_modem_node local_mutex_node mutex_client_node)
  roslaunch_add_file_check(launch/include/local_mutex.launch robot:=robot_0 robot_id:=11
                           DEPENDENCIES local_mutex_node mutex_client_node)
  roslaunch_add_file_check(launch/sounds_good.launch
                           DEPENDENCIES world_sim_node audio_propagation_node sounds_good_explorer_node task_monitor_node)
  roslaunch_add_file_check(launch/include/sounds_good_team.launch count:=2 mode:=bidirectional
                           DEPENDENCIES sounds_good_explorer_node)
  roslaunch_add_file_check(launch/charging_sim.launch
                           DEPENDENCIES world_sim_node audio_propagation_node local_mutex_node charging_demo_node)
  roslaunch_add_file_check(launch/include/charging_team.launch count:=2 chargers:=100
                           DEPENDENCIES local_mutex_node charging_demo_node)
  roslaunch_add_file_check(launch/charging_robot.launch robot_id:=11 chargers:=100
                           DEPENDENCIES nava_modem_node local_mutex_node charging_demo_node)
  roslaunch_add_file_check(launch/wanderer_robot.launch DEPENDENCIES nava_modem_node wanderer_node)
  # roslaunch-check wants a value for every arg, chargers too.
  foreach(task wanderer mutex charging)
    roslaunch_add_file_check(launch/team_robots.launch hosts:=localhost task:=${task} chargers:=100
                             DEPENDENCIES nava_modem_node wanderer_node local_mutex_node charging_demo_node)
  endforeach()
  foreach(launch_file record.launch replay.launch)
    roslaunch_add_file_check(launch/${launch_file} bag:=/tmp/check.bag)
  endforeach()
endif()
