#!/usr/bin/env bash
# ci/check-layers must fail on one planted violation of each rule, each alone in an otherwise
# clean scratch tree, and name the rule it broke. Without this, a check that never fails passes.
# The scratch tree has the layout of docs/profiles.md: one profile (a made-up one, P below) with
# its folders under every layer (<layer>/P/...), the shared folders beside them, headers under
# each module's include/ folder, private headers next to their users.
set -euo pipefail
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
P=demo

# put FILE CONTENT: write a file of the scratch tree.
put() { mkdir -p "$(dirname "$tmp/t/$1")"; printf '%b' "$2" > "$tmp/t/$1"; }

clean_tree() {
  rm -rf "$tmp/t"; mkdir -p "$tmp/t/ci"
  cp "$src/ci/check-layers" "$tmp/t/ci/"
  put protocol/$P/codec/include/protocol/$P/codec/layout.hpp '#include <cstdint>\n'
  put protocol/$P/CMakeLists.txt "add_library(ap_${P}_codec INTERFACE)\n"
  put core/$P/axis/include/core/$P/axis/axis.hpp "#include \"protocol/$P/codec/layout.hpp\"\n#include <array>\n"
  put core/$P/axis/src/axis.cpp "#include \"core/$P/axis/axis.hpp\"\n"
  put core/$P/axis/CMakeLists.txt "ap_core_library(ap_${P}_axis SOURCES src/axis.cpp DEPS ap_${P}_codec)\n"
  put firmware/$P/image.cpp "#include \"core/$P/axis/axis.hpp\"\n"
  put models/$P/echo/include/models/$P/echo/echo.hpp "#include \"core/$P/axis/axis.hpp\"\n#include <vector>\n"
  put models/$P/echo/CMakeLists.txt "add_library(ap_${P}_model_echo STATIC src/echo.cpp)
target_include_directories(ap_${P}_model_echo PUBLIC \${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(ap_${P}_model_echo PUBLIC ap_${P}_axis)\n"
  put pc/$P/client/include/pc/$P/client/client.hpp "#include \"core/$P/axis/axis.hpp\"\n#include \"ApBus.h\"\n#include <string>\n"
  put pc/$P/client/CMakeLists.txt "add_library(ap_${P}_client STATIC src/client.cpp)
target_include_directories(ap_${P}_client PUBLIC include)
target_link_libraries(ap_${P}_client
  PUBLIC ap_${P}_axis)\n"
  put sim/kit/include/sim/lockstep.hpp '#include <thread>\n'
  put sim/$P/include/sim/$P/board.hpp "#include \"pc/$P/client/client.hpp\"\n#include \"models/$P/echo/echo.hpp\"\n#include \"sim/lockstep.hpp\"\n"
  put sim/$P/CMakeLists.txt "add_library(ap_${P}_sim STATIC src/board.cpp)
target_include_directories(ap_${P}_sim PUBLIC \${CMAKE_CURRENT_SOURCE_DIR}/include)
target_link_libraries(ap_${P}_sim PUBLIC ap_${P}_client
  ap_${P}_model_echo)\n"
  # The tests' private rig, reached next to its user and, within properties/, through an
  # include path; a bare name the user's own layer has.
  put properties/$P/board/board_rig.hpp "#include \"sim/$P/board.hpp\"\n"
  put properties/$P/board/board_test.cpp "#include \"board_rig.hpp\"\n#include \"cli/anything.hpp\"\n#include <thread>\n"
  put properties/$P/path/path_test.cpp '#include "board_rig.hpp"\n'
  put properties/$P/path/CMakeLists.txt "target_include_directories(path_test PRIVATE \${CMAKE_SOURCE_DIR}/properties/$P/board)\n"
  put fuzz/kit/include/fuzz/script_reader.hpp '#include <cstdint>\n'
  put fuzz/$P/board/board.cpp "#include \"sim/$P/board.hpp\"\n#include \"fuzz/script_reader.hpp\"\n"
  put fuzz/$P/board/CMakeLists.txt "ap_add_fuzz_target(board SOURCES board.cpp LIBS ap_${P}_sim)\n"
  put bench/$P/axis_bench.cpp "#include \"core/$P/axis/axis.hpp\"\n"
  put cli/profile.hpp '#include <string>\n'
  put cli/$P/profile.cpp "#include \"profile.hpp\"\n#include \"sim/$P/board.hpp\"\n"
}

clean_tree
"$tmp/t/ci/check-layers" "$tmp/t" || { echo "clean tree rejected"; exit 1; }

# plant RULE FILE CONTENT EXPECTED-MESSAGE-FRAGMENT: CONTENT appended to FILE of a clean tree.
plant() {
  local rule=$1 file=$2 content=$3 expect=$4 out
  clean_tree
  mkdir -p "$(dirname "$tmp/t/$file")"
  printf '%b' "$content" >> "$tmp/t/$file"
  if out=$("$tmp/t/ci/check-layers" "$tmp/t" 2>&1); then echo "not caught: $rule"; exit 1; fi
  grep -qF -- "$expect" <<<"$out" || { echo "wrong message for $rule: $out"; exit 1; }
  echo "caught: $rule ($file)"
}
codec=protocol/$P/codec/include/protocol/$P/codec/layout.hpp
axis=core/$P/axis/include/core/$P/axis/axis.hpp
echo_h=models/$P/echo/include/models/$P/echo/echo.hpp
client=pc/$P/client/include/pc/$P/client/client.hpp
board=sim/$P/include/sim/$P/board.hpp
plant "protocol below core"        $codec "#include \"core/$P/axis/axis.hpp\"\n"     'protocol/ may not include core/'
plant "protocol MCU std subset"    $codec '#include <string>\n'                       '<string> is not in the MCU'
plant "core below models"          $axis "#include \"models/$P/echo/echo.hpp\"\n"    'core/ may not include models/'
plant "core below pc"              $axis "#include \"pc/$P/client/client.hpp\"\n"    'core/ may not include pc/'
plant "core MCU std subset"        $axis '#include <vector>\n'                        '<vector> is not in the MCU'
plant "core private header"        core/$P/axis/src/axis.cpp '#include "helper.hpp"\n' 'headers are included by path'
plant "firmware below sim"         firmware/$P/image.cpp "#include \"sim/$P/board.hpp\"\n"          'firmware/ may not include sim/'
plant "firmware below models"      firmware/$P/image.cpp "#include \"models/$P/echo/echo.hpp\"\n"   'firmware/ may not include models/'
plant "models below pc"            $echo_h "#include \"pc/$P/client/client.hpp\"\n"  'models/ may not include pc/'
plant "models below sim"           $echo_h "#include \"sim/$P/board.hpp\"\n"         'models/ may not include sim/'
plant "models below the shared sim kit" $echo_h '#include "sim/lockstep.hpp"\n'     'models/ may not include sim/'
plant "pc below models"            $client "#include \"models/$P/echo/echo.hpp\"\n"  'pc/ may not include models/'
plant "pc below sim"               $client "#include \"sim/$P/board.hpp\"\n"         'pc/ may not include sim/'
plant "sim below the tests"        $board "#include \"properties/$P/board/board_rig.hpp\"\n" 'sim/ may not include properties/'
plant "sim below the cli"          $board '#include "cli/profile.hpp"\n'              'sim/ may not include cli/'
plant "sim below the tests, <>"    $board "#include <properties/$P/board/board_rig.hpp>\n"   'sim/ may not include properties/'
plant "unknown layer header"       $board '#include "vendor/lib.hpp"\n'               'is not a header of any layer'
plant "every folder has a row"     $P/core.hpp '#include <cstdint>\n'                 "folder $P/ has no row"
plant "no C++ at the top"          stray.cpp '#include <cstdint>\n'                   'at the top level has no layer'
# Includes the first component does not show: a bare name reached through an include path
# into another layer, a relative path next to the user, and the include path itself.
plant "bare name into another layer" fuzz/$P/board/board.cpp '#include "board_rig.hpp"\n' \
      "\"board_rig.hpp\" is a bare name for properties/$P/board/board_rig.hpp"
plant "bare name from a shared folder" sim/kit/include/sim/lockstep.hpp '#include "board_rig.hpp"\n' \
      "\"board_rig.hpp\" is a bare name for properties/$P/board/board_rig.hpp"
plant "relative path into another layer" fuzz/$P/board/board.cpp "#include \"../../../properties/$P/board/board_rig.hpp\"\n" \
      "resolves next to its user to properties/$P/board/board_rig.hpp"
plant "include path into another layer" fuzz/$P/board/CMakeLists.txt \
      "target_include_directories(fuzz_board PRIVATE \${CMAKE_SOURCE_DIR}/properties/$P/board)\n" \
      "include path \${CMAKE_SOURCE_DIR}/properties/$P/board reaches into properties/"
plant "relative include path into another layer" fuzz/$P/board/CMakeLists.txt \
      "include_directories(\n  ../../../properties/$P/board)\n" 'reaches into properties/'
plant "include path below the layer"  models/$P/echo/CMakeLists.txt \
      "target_include_directories(ap_${P}_model_echo PRIVATE \${CMAKE_CURRENT_SOURCE_DIR}/../../../sim/$P/include)\n" \
      'reaches into sim/'
plant "link: pc below sim"         pc/$P/client/CMakeLists.txt "target_link_libraries(ap_${P}_client PRIVATE\n  ap_${P}_sim)\n" "pc/ may not link ap_${P}_sim"
plant "link: pc below models"      pc/$P/client/CMakeLists.txt "target_link_libraries(ap_${P}_client PRIVATE ap_${P}_model_echo)\n" "pc/ may not link ap_${P}_model_echo"
plant "link: models below pc"      models/$P/echo/CMakeLists.txt "target_link_libraries(ap_${P}_model_echo PUBLIC ap_${P}_client)\n" "models/ may not link ap_${P}_client"
plant "link: protocol below a core library" protocol/$P/CMakeLists.txt "target_link_libraries(ap_${P}_codec INTERFACE ap_${P}_axis)\n" \
      "protocol/ may not link ap_${P}_axis (a core/ library)"
plant "link through an include path" pc/$P/client/CMakeLists.txt \
      "target_include_directories(ap_${P}_client PRIVATE \$<TARGET_PROPERTY:ap_${P}_sim,INTERFACE_INCLUDE_DIRECTORIES>)\n" \
      "pc/ may not link ap_${P}_sim"
echo "planted violations caught"
