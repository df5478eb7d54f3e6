# ctest script: compiles main.cpp with only octoreach's include folder and Eigen's, then lists the
# headers it reads and fails if any belongs to FCL, OctoMap, urdfdom, TinyXML, KDL, assimp or Boost.
# (Those live in /usr/include here, which the compiler searches anyway: the header list, not a
# failed compile, is what proves they are not needed.)
# Inputs: CXX, SOURCE, INCLUDE_DIR, EIGEN_DIR.
set(flags -std=c++17 -Wall -Wextra -I${INCLUDE_DIR} -I${EIGEN_DIR})
execute_process(COMMAND ${CXX} ${flags} -fsyntax-only ${SOURCE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "public headers do not compile with Eigen alone:\n${out}${err}")
endif()
execute_process(COMMAND ${CXX} ${flags} -M ${SOURCE}
                RESULT_VARIABLE rc OUTPUT_VARIABLE deps ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "listing the headers of ${SOURCE} failed:\n${err}")
endif()
string(REGEX MATCHALL "[^ \\\\\n]*/(fcl|octomap|urdf_[a-z]+|urdfdom[a-z_]*|kdl|assimp|boost|ccd)/[^ \\\\\n]*|[^ \\\\\n]*tinyxml[^ \\\\\n]*"
       heavy "${deps}")
if(heavy)
  list(REMOVE_DUPLICATES heavy)
  list(GET heavy 0 first)
  message(FATAL_ERROR "public headers pull in dependency headers, e.g. ${first}:\n${heavy}")
endif()
string(REGEX MATCHALL "octoreach/[a-z_]+\\.hpp" read "${deps}")
list(REMOVE_DUPLICATES read)
message(STATUS "compiled with Eigen alone: ${read}")
