# flat2d_proto_library(NAME PROTOS a.proto ... [DEPS other_proto_libs...])
#
# Compiles .proto files (paths relative to the current folder) into a library. Every file
# is compiled under its path from the repository root, so "hal/can/x.proto" is what
# imports name, what the descriptor pool registers, and "hal/can/x.pb.h" what C++
# includes. Generated code is compiled without flat2d's -Werror warning set: it is
# protoc's code, not ours; nor in unity batches.
find_package(Protobuf REQUIRED)

function(flat2d_proto_library name)
  cmake_parse_arguments(ARG "" "" "PROTOS;DEPS" ${ARGN})
  set(generated)
  foreach(proto ${ARG_PROTOS})
    file(RELATIVE_PATH relative ${PROJECT_SOURCE_DIR} ${CMAKE_CURRENT_SOURCE_DIR}/${proto})
    string(REGEX REPLACE "\\.proto$" "" stem ${relative})
    set(outputs ${PROJECT_BINARY_DIR}/${stem}.pb.cc ${PROJECT_BINARY_DIR}/${stem}.pb.h)
    add_custom_command(
      OUTPUT ${outputs}
      COMMAND protobuf::protoc --cpp_out=${PROJECT_BINARY_DIR} -I ${PROJECT_SOURCE_DIR} ${relative}
      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${proto} protobuf::protoc
      COMMENT "protoc ${relative}"
      VERBATIM)
    list(APPEND generated ${outputs})
  endforeach()
  add_library(${name} ${generated})
  # Every .pb.cc defines the same file-static tables (schemas, file_default_instances).
  set_target_properties(${name} PROPERTIES UNITY_BUILD OFF)
  target_link_libraries(${name} PUBLIC protobuf::libprotobuf ${ARG_DEPS})
  target_include_directories(${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_BINARY_DIR}>)
endfunction()
