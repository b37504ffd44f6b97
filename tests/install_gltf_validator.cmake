# CTest fixture: installs the Khronos glTF Validator (npm package gltf-validator, VERSION) into
# PREFIX/node_modules once; later runs find it there and do nothing. Without npm it only says so:
# the validator tests then skip when node is missing too (scripts/deps.sh installs both).
# Usage: cmake -DPREFIX=<dir> -DVERSION=<version> -P install_gltf_validator.cmake
set(pkg "${PREFIX}/node_modules/gltf-validator/package.json")
if(EXISTS "${pkg}")
  file(READ "${pkg}" manifest)
  string(JSON installed ERROR_VARIABLE json_error GET "${manifest}" version)
  if(installed STREQUAL VERSION)
    message(STATUS "gltf-validator ${VERSION} already in ${PREFIX}")
    return()
  endif()
endif()
find_program(NPM npm)
if(NOT NPM)
  message(STATUS "npm not found: gltf-validator not installed (the validator tests skip without node)")
  return()
endif()
file(MAKE_DIRECTORY "${PREFIX}")
execute_process(COMMAND "${NPM}" install --prefix "${PREFIX}" --no-audit --no-fund --loglevel=error
                        "gltf-validator@${VERSION}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT EXISTS "${pkg}")
  message(FATAL_ERROR "npm install gltf-validator@${VERSION} into ${PREFIX} failed (exit ${rc})")
endif()
message(STATUS "installed gltf-validator ${VERSION} into ${PREFIX}")
