# The ROS 1 layer: ehd_capsule_node over ehd_core. Included only when catkin is found.
include_directories(${catkin_INCLUDE_DIRS})
file(GLOB EHD_ROS_SOURCES CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/src/ros/*.cpp)
if(EHD_ROS_SOURCES)
  add_executable(ehd_capsule_node ${EHD_ROS_SOURCES})
  target_include_directories(ehd_capsule_node PRIVATE ${catkin_INCLUDE_DIRS}
                             ${CATKIN_DEVEL_PREFIX}/${CATKIN_GLOBAL_INCLUDE_DESTINATION})
  target_link_libraries(ehd_capsule_node PRIVATE ehd_core ${catkin_LIBRARIES})
  target_compile_options(ehd_capsule_node PRIVATE ${EHD_WARNINGS})
  add_dependencies(ehd_capsule_node ${PROJECT_NAME}_generate_messages_cpp ${PROJECT_NAME}_gencfg)
endif()
