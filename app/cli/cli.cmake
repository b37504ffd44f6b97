# sublift-cli: every command of the modeler without a display (docs/cli.md).
add_executable(sublift-cli
  ${CMAKE_CURRENT_LIST_DIR}/cli_main.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_info.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_render.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_convert.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_args.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_json.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_hierarchy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_subdivide.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_analyze.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_rebuild.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_fit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_synthesize.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_edit.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_set.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_info_hierarchy.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_basis.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_basis_png.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_ffd.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_animation.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_coefficients.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_experiment.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_resample_sphere.cpp
  ${CMAKE_CURRENT_LIST_DIR}/cli_compress.cpp
)
target_include_directories(sublift-cli PRIVATE ${PROJECT_SOURCE_DIR})
target_link_libraries(sublift-cli PRIVATE sublift_core nlohmann_json::nlohmann_json)
# The triangle schemes' coefficient tables solve small dense systems (core/schemes/tri/tri_gram.h).
target_link_libraries(sublift-cli PRIVATE Eigen3::Eigen)
if(SUBLIFT_WITH_GUI)
  target_link_libraries(sublift-cli PRIVATE sublift_render)
  target_compile_definitions(sublift-cli PRIVATE SUBLIFT_HAVE_RENDER=1)
endif()
