# sublift_modeler_state: the modeler's document (ModelerState: hierarchy, session, undo, files,
# compression, FFD and basis views) and its script runner. No GL, no ImGui and no ui/ code
# (only ui/'s plain-data headers), so it is built in every configuration: the sanitizer build
# runs the modeler soak test and fuzzes modeler scripts through it (docs/fuzzing.md).
add_library(sublift_modeler_state STATIC
  ${CMAKE_CURRENT_LIST_DIR}/animation_view_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/basis_view_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_animation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_state.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_tools.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_uv.cpp
  ${CMAKE_CURRENT_LIST_DIR}/modeler_attributes.cpp
  ${CMAKE_CURRENT_LIST_DIR}/script_runner.cpp
)
target_include_directories(sublift_modeler_state PUBLIC ${PROJECT_SOURCE_DIR})
target_link_libraries(sublift_modeler_state PUBLIC sublift_core PRIVATE nlohmann_json::nlohmann_json)
