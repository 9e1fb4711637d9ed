# Warnings on for our own targets only (third-party headers are included as SYSTEM by their imported targets).
function(reamsim_target_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wno-unused-parameter)
endfunction()

# One helper to declare a module library with the layout modules/<name>/{include,src}.
function(reamsim_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(reamsim_${name} ${ARG_SOURCES})
  add_library(reamsim::${name} ALIAS reamsim_${name})
  target_include_directories(reamsim_${name} PUBLIC ${CMAKE_CURRENT_SOURCE_DIR}/include)
  target_link_libraries(reamsim_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  reamsim_target_warnings(reamsim_${name})
endfunction()
