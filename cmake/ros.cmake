# The ROS 1 layer: ehd_capsule_node over ehd_core. Included only when catkin is found.
# The node's parts (parameters, recorder, publishers, run controller, messages) are a library,
# so that the unit tests in test/ros/*_test.cpp link them without main().
file(GLOB EHD_ROS_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/ros/*.cpp)
list(FILTER EHD_ROS_SOURCES EXCLUDE REGEX "/main\\.cpp$")
if(EHD_ROS_SOURCES)
  add_library(ehd_ros_node STATIC ${EHD_ROS_SOURCES})
  target_include_directories(ehd_ros_node PUBLIC ${catkin_INCLUDE_DIRS}
                             ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
  target_link_libraries(ehd_ros_node PUBLIC ehd_core ${catkin_LIBRARIES})
  # The core's flags too: Eigen's alignment (EIGEN_MAX_ALIGN_BYTES) follows -march, and with
  # different alignments a matrix the core allocates (Simulation::VertexVelocity) and the node
  # frees goes through two different allocators ("double free or corruption" at the first
  # speed-coloured surface), besides breaking the one-definition rule for every inlined Eigen
  # function the two share.
  target_compile_options(ehd_ros_node PRIVATE ${EHD_WARNINGS} ${EHD_CORE_OPT})
  add_dependencies(ehd_ros_node ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)
  add_executable(ehd_capsule_node ${CMAKE_CURRENT_SOURCE_DIR}/src/ros/main.cpp)
  target_link_libraries(ehd_capsule_node PRIVATE ehd_ros_node)
  target_compile_options(ehd_capsule_node PRIVATE ${EHD_WARNINGS} ${EHD_CORE_OPT})
endif()

# Integration tests: rostest launch files in test/ros/, run by CTest one at a time (each starts its
# own roscore on the rostest port).
if(EHD_BUILD_TESTS AND CATKIN_ENABLE_TESTING AND EHD_ROS_SOURCES)
  find_package(rostest REQUIRED)
  file(GLOB EHD_ROSTESTS RELATIVE ${CMAKE_CURRENT_SOURCE_DIR} CONFIGURE_DEPENDS
       ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/*.test)
  # Script tests of the whole node, one master each (so they run alone: RUN_SERIAL):
  #   ros_exit_codes: scripts/run returns the node's exit status (roslaunch does not);
  #   ros_live_output: scripts/run's output comes live through a pipe, no cmake lines when up to
  #     date; ros_stale_parameters: with a kept roscore, no launch or rosrun takes an earlier
  #     run's parameters silently; ros_bag_path: a relative bag path is the caller's directory's;
  #   ros_recording_rate: a recording logs its bytes per state, MB/s and free space, and warns
  #     before the disk fills; ros_measures_3d: 3D progress lines show D_z and the volume drift.
  foreach(pair "exit_codes:exit_codes.sh" "live_output:live_output_test.py"
               "stale_parameters:stale_parameters_test.py" "bag_path:bag_path_test.py"
               "recording_rate:recording_rate_test.py" "measures_3d:measures_3d_test.py")
    string(REPLACE ":" ";" parts ${pair})
    list(GET parts 0 name)
    list(GET parts 1 script)
    add_test(NAME ros_${name} COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/${script})
    set_tests_properties(ros_${name} PROPERTIES RUN_SERIAL TRUE TIMEOUT 300
                         LABELS "ros;integration")
  endforeach()
  set_tests_properties(ros_live_output PROPERTIES TIMEOUT 600)
  # One launch that takes scene:=, thin includes of it per scene, doc= on every argument.
  add_test(NAME ros_launch_files COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/launch_files_test.py)
  set_tests_properties(ros_launch_files PROPERTIES TIMEOUT 300 LABELS "ros;integration")
  # scripts/plot_bag's choices per dimension and scene (t unit, title, panels, section), on bags
  # the test writes itself (rosbag and the package's messages; no master).
  add_test(NAME ros_plot_bag COMMAND ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/plot_bag_test.py)
  set_tests_properties(ros_plot_bag PROPERTIES TIMEOUT 300 LABELS "ros;integration")
  # Unit tests of the node's parts that need no ROS master (GoogleTest, test/ros/*_test.cpp).
  file(GLOB EHD_ROS_UNIT_TESTS CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/test/ros/*_test.cpp)
  foreach(test_source ${EHD_ROS_UNIT_TESTS})
    get_filename_component(test_name ${test_source} NAME_WE)
    set(test_target ros_${test_name})
    add_executable(${test_target} ${test_source})
    target_link_libraries(${test_target} PRIVATE ehd_ros_node ehd_test_support GTest::gtest
                                                 GTest::gtest_main)
    target_compile_options(${test_target} PRIVATE ${EHD_WARNINGS} ${EHD_CORE_OPT})
    set_target_properties(${test_target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${EHD_BIN_DIR}/test)
    add_test(NAME ${test_target} COMMAND ${test_target}
             WORKING_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_tests_properties(${test_target} PROPERTIES LABELS "unit;ros" TIMEOUT 120)
  endforeach()
  foreach(rostest_file ${EHD_ROSTESTS})
    add_rostest(${rostest_file} DEPENDENCIES ehd_capsule_node)
    string(REPLACE "/" "_" rostest_name ${rostest_file})
    set_tests_properties(_ctest_${PROJECT_NAME}_rostest_${rostest_name}
                         PROPERTIES RUN_SERIAL TRUE TIMEOUT 300 LABELS "ros;integration")
  endforeach()
endif()
