# The `sublift` GUI executable; included from app/CMakeLists.txt when SUBLIFT_WITH_GUI is on.
# sublift_modeler holds the modeler's controller and view so GUI tests can drive the controller
# without a window; it builds on sublift_modeler_state (modeler_state.cmake), which is GL-free.
add_library(sublift_modeler STATIC
  ${CMAKE_CURRENT_LIST_DIR}/modeler_controller.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_view.cpp
)
target_include_directories(sublift_modeler PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(sublift_modeler PUBLIC sublift_modeler_state sublift_core sublift_render sublift_ui)

add_executable(sublift
  ${CMAKE_CURRENT_LIST_DIR}/sublift_main.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gui_app.cpp
)
target_include_directories(sublift PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(sublift PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
target_link_libraries(sublift PRIVATE sublift_modeler sublift_core sublift_render sublift_ui)
