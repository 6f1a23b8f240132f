# Compiles compute shaders with glslangValidator at build time (with a
# depfile, so edits to included files rebuild) and embeds the SPIR-V in a
# static library. For each shaders/NAME.comp the library defines
#   extern const std::uint32_t kSpirv_NAME[]; extern const std::size_t kSpirvSize_NAME;
# (size in bytes) declared in <strata_spirv.h>. VARIANTS entries
# NAME=shaders/SRC.comp:DEFINE[,DEFINE...] compile SRC again with -DDEFINE
# for each as kSpirv_NAME
# (a variant that compiles code out rather than leaving it to a
# specialization constant: the driver then never sees it). The .spv files
# stay in ${CMAKE_BINARY_DIR}/spirv for spirv-val in the tests. GENERATED
# lists headers written at build time (absolute paths): their folders are
# include folders and every shader depends on them.
find_program(GLSLANG_VALIDATOR glslangValidator REQUIRED)

function(strata_add_shaders target)
  cmake_parse_arguments(ARG "" "" "SHADERS;VARIANTS;INCLUDE_DIRS;GENERATED" ${ARGN})
  set(spv_dir ${CMAKE_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${spv_dir})
  set(inc_flags "")
  foreach(dir ${ARG_INCLUDE_DIRS})
    list(APPEND inc_flags "-I${CMAKE_SOURCE_DIR}/${dir}")  # glslang 12 wants no space
  endforeach()
  foreach(file ${ARG_GENERATED})
    get_filename_component(dir ${file} DIRECTORY)
    list(APPEND inc_flags "-I${dir}")
  endforeach()
  list(REMOVE_DUPLICATES inc_flags)
  set(gen_sources "")
  set(decls "")
  set(entries "")
  foreach(shader ${ARG_SHADERS})
    get_filename_component(name ${shader} NAME_WE)
    list(APPEND entries "${name}=${shader}:")
  endforeach()
  list(APPEND entries ${ARG_VARIANTS})
  foreach(entry ${entries})
    string(REGEX MATCH "^([A-Za-z0-9_]+)=([^:]+):(.*)$" ok "${entry}")
    if(NOT ok)
      message(FATAL_ERROR "strata_add_shaders: bad entry '${entry}'")
    endif()
    set(name ${CMAKE_MATCH_1})
    set(shader ${CMAKE_MATCH_2})
    set(define_flags "")
    if(CMAKE_MATCH_3)
      string(REPLACE "," ";" defines "${CMAKE_MATCH_3}")
      foreach(define ${defines})
        list(APPEND define_flags "-D${define}")
      endforeach()
    endif()
    set(spv ${spv_dir}/${name}.spv)
    set(hdr ${spv_dir}/${name}.spv.h)
    add_custom_command(
      OUTPUT ${spv} ${hdr}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.1 ${inc_flags} ${define_flags}
              --depfile ${spv}.d -o ${spv} ${CMAKE_SOURCE_DIR}/${shader}
      COMMAND ${GLSLANG_VALIDATOR} --target-env vulkan1.1 ${inc_flags} ${define_flags}
              --vn kSpirv_${name} -o ${hdr} ${CMAKE_SOURCE_DIR}/${shader}
      DEPENDS ${CMAKE_SOURCE_DIR}/${shader} ${ARG_GENERATED}
      DEPFILE ${spv}.d
      COMMENT "glslangValidator ${shader} ${define_flags}"
      VERBATIM)
    set(cpp ${spv_dir}/${name}.spv.cpp)
    file(GENERATE OUTPUT ${cpp} CONTENT
"#include <cstddef>\n#include <cstdint>\n#include \"${name}.spv.h\"\nextern const std::size_t kSpirvSize_${name} = sizeof(kSpirv_${name});\nextern const std::uint32_t* const kSpirvPtr_${name} = kSpirv_${name};\n")
    set_source_files_properties(${cpp} PROPERTIES OBJECT_DEPENDS ${hdr})
    list(APPEND gen_sources ${cpp})
    string(APPEND decls "extern const std::size_t kSpirvSize_${name};\nextern const std::uint32_t* const kSpirvPtr_${name};\n")
  endforeach()
  file(GENERATE OUTPUT ${spv_dir}/strata_spirv.h CONTENT
"#pragma once\n#include <cstddef>\n#include <cstdint>\n${decls}")
  add_library(${target} STATIC ${gen_sources})
  target_include_directories(${target} PUBLIC ${spv_dir})
endfunction()
