#!/usr/bin/env bash
# ci/check-layers must fail on one planted violation of each rule, each alone in an otherwise
# clean scratch tree, and name the rule it broke. Without this, a check that never fails passes.
set -euo pipefail
src=$1
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT

clean_tree() {
  rm -rf "$tmp/t"; mkdir -p "$tmp/t/ci"
  cp "$src/ci/check-layers" "$tmp/t/ci/"
  local d
  for d in protocol/xy/codec core/xy/axis firmware/xy models/xy/echo pc/xy/client sim properties/x fuzz/x bench cli; do
    mkdir -p "$tmp/t/$d"
  done
  printf '#include <cstdint>\n' > "$tmp/t/protocol/xy/codec/layout.hpp"
  printf '#include "protocol/xy/codec/layout.hpp"\n#include <array>\n' > "$tmp/t/core/xy/axis/axis.hpp"
  printf '#include "core/xy/axis/axis.hpp"\n' > "$tmp/t/firmware/xy/image.cpp"
  printf '#include "core/xy/axis/axis.hpp"\n#include <vector>\n' > "$tmp/t/models/xy/echo/echo.hpp"
  printf '#include "core/xy/axis/axis.hpp"\n#include "ApBus.h"\n#include <string>\n' > "$tmp/t/pc/xy/client/client.hpp"
  printf '#include "pc/xy/client/client.hpp"\n#include "models/xy/echo/echo.hpp"\n#include "sim/xy/board.hpp"\n' > "$tmp/t/sim/board.hpp"
  printf '#include "sim/xy/board.hpp"\n#include "cli/anything.hpp"\n#include <thread>\n' > "$tmp/t/properties/x/test.cpp"
  printf 'add_library(ap_xy_model_echo STATIC echo.cpp)\ntarget_link_libraries(ap_xy_model_echo PUBLIC ap_xy_axis)\n' > "$tmp/t/models/xy/echo/CMakeLists.txt"
  printf 'add_library(ap_xy_client STATIC client.cpp)\ntarget_link_libraries(ap_xy_client\n  PUBLIC ap_xy_frame)\n' > "$tmp/t/pc/xy/client/CMakeLists.txt"
  printf 'add_library(ap_xy_sim STATIC board.cpp)\ntarget_link_libraries(ap_xy_sim PUBLIC ap_xy_client\n  ap_xy_model_echo)\n' > "$tmp/t/sim/CMakeLists.txt"
}

clean_tree
"$tmp/t/ci/check-layers" "$tmp/t" || { echo "clean tree rejected"; exit 1; }

# plant RULE FILE CONTENT EXPECTED-MESSAGE-FRAGMENT
plant() {
  local rule=$1 file=$2 content=$3 expect=$4 out
  clean_tree
  mkdir -p "$(dirname "$tmp/t/$file")"
  printf '%b' "$content" >> "$tmp/t/$file"
  if out=$("$tmp/t/ci/check-layers" "$tmp/t"); then echo "not caught: $rule"; exit 1; fi
  grep -qF -- "$expect" <<<"$out" || { echo "wrong message for $rule: $out"; exit 1; }
  echo "caught: $rule"
}
plant "protocol below core"        protocol/xy/codec/layout.hpp '#include "core/xy/axis/axis.hpp"\n' 'protocol/ may not include core/'
plant "protocol MCU std subset"    protocol/xy/codec/layout.hpp '#include <string>\n'             '<string> is not in the MCU'
plant "core below models"          core/xy/axis/axis.hpp  '#include "models/xy/echo/echo.hpp"\n'      'core/ may not include models/'
plant "core below pc"              core/xy/axis/axis.hpp  '#include "pc/xy/client/client.hpp"\n'      'core/ may not include pc/'
plant "core MCU std subset"        core/xy/axis/axis.hpp  '#include <vector>\n'                    '<vector> is not in the MCU'
plant "core private header"        core/xy/axis/axis.hpp  '#include "helper.hpp"\n'                'headers are included by path'
plant "firmware below sim"         firmware/xy/image.cpp '#include "sim/xy/board.hpp"\n'           'firmware/ may not include sim/'
plant "firmware below models"      firmware/xy/image.cpp '#include "models/xy/echo/echo.hpp"\n'    'firmware/ may not include models/'
plant "models below pc"            models/xy/echo/echo.hpp '#include "pc/xy/client/client.hpp"\n'     'models/ may not include pc/'
plant "models below sim"           models/xy/echo/echo.hpp '#include "sim/xy/board.hpp"\n'            'models/ may not include sim/'
plant "pc below models"            pc/xy/client/client.hpp '#include "models/xy/echo/echo.hpp"\n'     'pc/ may not include models/'
plant "pc below sim"               pc/xy/client/client.hpp '#include "sim/xy/board.hpp"\n'            'pc/ may not include sim/'
plant "sim below the tests"        sim/xy/board.hpp '#include "properties/x/rig.hpp"\n'            'sim/ may not include properties/'
plant "sim below the cli"          sim/xy/board.hpp '#include "cli/cli.hpp"\n'                     'sim/ may not include cli/'
plant "unknown layer header"       sim/xy/board.hpp '#include "vendor/lib.hpp"\n'                  'is not a header of any layer'
plant "every folder has a row"     unit3/core.hpp '#include <cstdint>\n'                        'folder unit3/ has no row'
plant "no C++ at the top"          stray.cpp '#include <cstdint>\n'                             'at the top level has no layer'
plant "link: pc below sim"         pc/xy/client/CMakeLists.txt 'target_link_libraries(ap_xy_client PRIVATE\n  ap_xy_sim)\n' 'pc/ may not link ap_xy_sim'
plant "link: pc below models"      pc/xy/client/CMakeLists.txt 'target_link_libraries(ap_xy_client PRIVATE ap_xy_model_echo)\n' 'pc/ may not link ap_xy_model_echo'
plant "link: models below pc"      models/xy/echo/CMakeLists.txt 'target_link_libraries(ap_xy_model_echo PUBLIC ap_xy_client)\n' 'models/ may not link ap_xy_client'
echo "planted violations caught"
