# Tests of render/, ui/ and the `sublift` GUI; included from tests/CMakeLists.txt when
# SUBLIFT_WITH_GUI is on. gui_test runs the real executable under xvfb-run and without any
# display, so it needs xvfb, xauth and Mesa's EGL (TOOLCHAIN.md); missing ones fail, not skip.
include(GoogleTest)
# Shared helpers are included as "tests/..." (tests/ mirrors the code, helpers stay at its root).
include_directories(${PROJECT_SOURCE_DIR})

add_executable(camera_test ${CMAKE_CURRENT_LIST_DIR}/render/camera_test.cpp)
target_link_libraries(camera_test PRIVATE sublift_render GTest::gtest_main)
gtest_discover_tests(camera_test DISCOVERY_MODE PRE_TEST)

add_executable(viewport_input_test ${CMAKE_CURRENT_LIST_DIR}/ui/viewport_input_test.cpp)
target_link_libraries(viewport_input_test PRIVATE sublift_ui GTest::gtest_main)
gtest_discover_tests(viewport_input_test DISCOVERY_MODE PRE_TEST)

add_executable(render_test ${CMAKE_CURRENT_LIST_DIR}/render/render_test.cpp)
target_link_libraries(render_test PRIVATE sublift_render PkgConfig::STB GTest::gtest_main)
gtest_discover_tests(render_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 60)

add_executable(gui_test ${CMAKE_CURRENT_LIST_DIR}/modeler/gui_test.cpp)
target_link_libraries(gui_test PRIVATE PkgConfig::STB GTest::gtest_main)
target_compile_definitions(gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
add_dependencies(gui_test sublift)
gtest_discover_tests(gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)

# The modeler's limit surface and control net renderers (issue 4); PNGs go to the build folder.
add_executable(modeler_render_test ${CMAKE_CURRENT_LIST_DIR}/render/modeler_render_test.cpp)
target_link_libraries(modeler_render_test PRIVATE sublift_render GTest::gtest_main)
target_compile_definitions(modeler_render_test PRIVATE
  SUBLIFT_TEST_PNG_DIR="${CMAKE_CURRENT_BINARY_DIR}/modeler_render_png")
gtest_discover_tests(modeler_render_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 60)

# The modeler: key/mouse bindings as data, and `sublift --script` end to end (Xvfb and EGL).
add_executable(modeler_keys_test ${CMAKE_CURRENT_LIST_DIR}/ui/modeler_keys_test.cpp)
target_link_libraries(modeler_keys_test PRIVATE sublift_ui GTest::gtest_main)
gtest_discover_tests(modeler_keys_test DISCOVERY_MODE PRE_TEST)

add_executable(modeler_gui_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_gui_test.cpp)
target_link_libraries(modeler_gui_test PRIVATE PkgConfig::STB GTest::gtest_main)
target_compile_definitions(modeler_gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets"
  SUBLIFT_TEST_OUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/modeler_gui_test_out")
add_dependencies(modeler_gui_test sublift)
gtest_discover_tests(modeler_gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)

# The modeler's mouse and keys on the controller, without a window or GL context.
add_executable(modeler_controller_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_controller_test.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_tools_test.cpp)
target_link_libraries(modeler_controller_test PRIVATE sublift_modeler GTest::gtest_main)
target_compile_definitions(modeler_controller_test PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets"
  SUBLIFT_SHARED_DATA="${SUBLIFT_SHARED_DATA}")
gtest_discover_tests(modeler_controller_test DISCOVERY_MODE PRE_TEST)

# The modeler keeps a model's UVs and attribute channels (issue 20), on ModelerState without a window.
add_executable(modeler_channels_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_channels_test.cpp)
target_link_libraries(modeler_channels_test PRIVATE sublift_modeler sublift_testing GTest::gtest_main)
target_compile_definitions(modeler_channels_test PRIVATE SUBLIFT_SHARED_DATA="${SUBLIFT_SHARED_DATA}"
  SUBLIFT_CLI="$<TARGET_FILE:sublift-cli>")
add_dependencies(modeler_channels_test sublift-cli)
gtest_discover_tests(modeler_channels_test DISCOVERY_MODE PRE_TEST)

# The modeler's animation mode (docs/animation.md) on ModelerState, without a window.
add_executable(modeler_animation_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_animation_test.cpp)
target_link_libraries(modeler_animation_test PRIVATE sublift_modeler GTest::gtest_main)
gtest_discover_tests(modeler_animation_test DISCOVERY_MODE PRE_TEST)
add_executable(modeler_animation_gui_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_animation_gui_test.cpp)
target_link_libraries(modeler_animation_gui_test PRIVATE PkgConfig::STB GTest::gtest_main)
target_compile_definitions(modeler_animation_gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_SHARED_DATA="${SUBLIFT_SHARED_DATA}"
  SUBLIFT_TEST_OUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/modeler_animation_gui_out")
add_dependencies(modeler_animation_gui_test sublift)
gtest_discover_tests(modeler_animation_gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)

# The modeler's compression view (docs/compression.md): on the controller, and `sublift --script`
# under Xvfb with screenshots (PNGs in modeler_compress_gui_out/).
add_executable(modeler_compress_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_compress_test.cpp)
target_link_libraries(modeler_compress_test PRIVATE sublift_modeler GTest::gtest_main)
target_compile_definitions(modeler_compress_test PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets")
gtest_discover_tests(modeler_compress_test DISCOVERY_MODE PRE_TEST)
# A model's attribute channel shown as colour, `sublift --script` under Xvfb (issue 20).
add_executable(modeler_channels_gui_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_channels_gui_test.cpp)
target_link_libraries(modeler_channels_gui_test PRIVATE PkgConfig::STB GTest::gtest_main)
target_compile_definitions(modeler_channels_gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_SHARED_DATA="${SUBLIFT_SHARED_DATA}"
  SUBLIFT_TEST_OUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/modeler_channels_gui_out")
add_dependencies(modeler_channels_gui_test sublift)
gtest_discover_tests(modeler_channels_gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)

add_executable(modeler_compress_gui_test ${CMAKE_CURRENT_LIST_DIR}/modeler/modeler_compress_gui_test.cpp)
target_link_libraries(modeler_compress_gui_test PRIVATE sublift_core PkgConfig::STB GTest::gtest_main)
target_compile_definitions(modeler_compress_gui_test PRIVATE
  SUBLIFT_GUI_EXE="$<TARGET_FILE:sublift>"
  SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets"
  SUBLIFT_TEST_OUT_DIR="${CMAKE_CURRENT_BINARY_DIR}/modeler_compress_gui_out")
add_dependencies(modeler_compress_gui_test sublift)
gtest_discover_tests(modeler_compress_gui_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120 LABELS gui)

# sublift-cli render on meshes, lattices and projects, PNGs decoded (issue 19).
add_executable(cli_render_test ${CMAKE_CURRENT_LIST_DIR}/render/cli_render_test.cpp)
target_link_libraries(cli_render_test PRIVATE sublift_core sublift_testing PkgConfig::STB GTest::gtest_main)
target_compile_definitions(cli_render_test PRIVATE SUBLIFT_ASSETS_DIR="${PROJECT_SOURCE_DIR}/assets"
  SUBLIFT_SHARED_DATA="${SUBLIFT_SHARED_DATA}" SUBLIFT_CLI="$<TARGET_FILE:sublift-cli>")
add_dependencies(cli_render_test sublift-cli)
gtest_discover_tests(cli_render_test DISCOVERY_MODE PRE_TEST PROPERTIES TIMEOUT 120)
