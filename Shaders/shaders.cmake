# lightsolver_embed_shaders(<target> [NAMED] <shader.comp>...): compiles each compute shader with
# glslc (found by find_package(Vulkan COMPONENTS glslc); its cache path works in every directory)
# (Vulkan 1.2 SPIR-V, -O, includes from this folder) into <name>.spv.inc, a comma-separated list
# of uint32 words that C++ includes inside an array initialiser. The folder with the .inc files
# and this folder (for trace_bindings.h, the binding numbers shared by C++ and GLSL; shared/, the
# physics both include, is on lightsolver_lib's public path anyway) are added to <target>'s
# include path. Dependencies on #included files come from glslc's depfile, so editing
# any shader rebuilds exactly what uses it. NAMED: compiled without -O into <name>.named.spv.inc,
# which keeps the OpName of blocks and constants that -O strips (for tests that reflect them).
set(LIGHTSOLVER_SHADER_DIR ${CMAKE_CURRENT_LIST_DIR})

function(lightsolver_embed_shaders target)
  cmake_parse_arguments(PARSE_ARGV 1 arg "NAMED" "" "")
  set(out_dir ${CMAKE_CURRENT_BINARY_DIR}/spirv)
  file(MAKE_DIRECTORY ${out_dir})
  if(arg_NAMED)
    set(suffix .named)
    set(optimise)
  else()
    set(suffix)
    set(optimise -O)
  endif()
  set(outputs)
  foreach(source ${arg_UNPARSED_ARGUMENTS})
    get_filename_component(name ${source} NAME_WE)
    set(out ${out_dir}/${name}${suffix}.spv.inc)
    add_custom_command(
      OUTPUT ${out}
      COMMAND ${Vulkan_GLSLC_EXECUTABLE} --target-env=vulkan1.2 ${optimise} -I ${LIGHTSOLVER_SHADER_DIR}
              -mfmt=num -MD -MF ${out}.d -o ${out} ${source}
      DEPENDS ${source}
      DEPFILE ${out}.d
      COMMENT "glslc ${name}.comp${suffix}"
      VERBATIM)
    list(APPEND outputs ${out})
  endforeach()
  add_custom_target(${target}_spirv${suffix} DEPENDS ${outputs})
  add_dependencies(${target} ${target}_spirv${suffix})
  target_include_directories(${target} PRIVATE ${out_dir} ${LIGHTSOLVER_SHADER_DIR})
endfunction()
