# The `sublift` GUI executable; included from app/CMakeLists.txt when SUBLIFT_WITH_GUI is on.
# sublift_modeler holds the modeler's state, controller, view and script runner so GUI tests can
# drive the controller without a window.
add_library(sublift_modeler STATIC
  ${CMAKE_CURRENT_LIST_DIR}/basis_view_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_controller.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_view.cpp
  ${CMAKE_CURRENT_LIST_DIR}/script_runner.cpp
)
target_include_directories(sublift_modeler PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(sublift_modeler PUBLIC sublift_core sublift_render sublift_ui)

add_executable(sublift
  ${CMAKE_CURRENT_LIST_DIR}/sublift_main.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gui_app.cpp
)
target_include_directories(sublift PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(sublift PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
target_link_libraries(sublift PRIVATE sublift_modeler sublift_core sublift_render sublift_ui)
