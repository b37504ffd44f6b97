# The `sublift` GUI executable; included from app/CMakeLists.txt when SUBLIFT_WITH_GUI is on.
add_executable(sublift
  ${CMAKE_CURRENT_LIST_DIR}/sublift_main.cpp
  ${CMAKE_CURRENT_LIST_DIR}/gui_app.cpp
)
target_include_directories(sublift PRIVATE ${PROJECT_SOURCE_DIR})
target_compile_definitions(sublift PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
target_link_libraries(sublift PRIVATE sublift_core sublift_render sublift_ui)
