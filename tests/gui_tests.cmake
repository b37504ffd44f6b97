# Tests of render/, ui/ and the `sublift` GUI; included from tests/CMakeLists.txt when
# SUBLIFT_WITH_GUI is on. gui_test runs the real executable under xvfb-run and without any
# display, so it needs xvfb, xauth and Mesa's EGL (TOOLCHAIN.md); missing ones fail, not skip.
include(GoogleTest)

add_executable(camera_test ${CMAKE_CURRENT_LIST_DIR}/camera_test.cpp)
target_link_libraries(camera_test PRIVATE sublift_render GTest::gtest_main)
gtest_discover_tests(camera_test DISCOVERY_MODE PRE_TEST)

add_executable(viewport_input_test ${CMAKE_CURRENT_LIST_DIR}/viewport_input_test.cpp)
target_link_libraries(viewport_input_test PRIVATE sublift_ui GTest::gtest_main)
gtest_discover_tests(viewport_input_test DISCOVERY_MODE PRE_TEST)

add_executable(render_test ${CMAKE_CURRENT_LIST_DIR}/render_test.cpp)
target_link_libraries(render_test PRIVATE sublift_render PkgConfig::STB GTest::gtest_main)
gtest_discover_tests(render_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 60)

add_executable(gui_test ${CMAKE_CURRENT_LIST_DIR}/gui_test.cpp)
target_link_libraries(gui_test PRIVATE PkgConfig::STB GTest::gtest_main)
target_compile_definitions(gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
add_dependencies(gui_test sublift)
gtest_discover_tests(gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)
