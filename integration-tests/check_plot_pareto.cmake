# scripts/plot-pareto.py on bench.tiny_sweep_interleaved's pareto.json (DIR) with PYTHON, into OUT:
# each of its three plots as an SVG and a PNG, non-empty, each file what its name says.
if(NOT PYTHON)
  message(FATAL_ERROR "no python3 with matplotlib was found when configuring (TYNDALL_PLOT_PYTHON): "
                      "apt-get install python3-matplotlib (scripts/install-deps.sh), then configure again")
endif()
include("${CMAKE_CURRENT_LIST_DIR}/check_common.cmake")
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${PYTHON}" "${SCRIPT}" "${DIR}/pareto.json" "${OUT}" RESULT_VARIABLE status)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "plot-pareto.py failed (${status})")
endif()
foreach(stem pareto-64x36-256 pareto-64x36-256-directional pareto-64x36-256-local)
  foreach(ext svg png)
    expect_nonempty_file("${OUT}/${stem}.${ext}" plot-pareto.py)
  endforeach()
  # The PNG signature; an XML document whose root is an SVG element.
  file(READ "${OUT}/${stem}.png" signature LIMIT 8 HEX)
  if(NOT signature STREQUAL "89504e470d0a1a0a")
    message(FATAL_ERROR "${OUT}/${stem}.png starts with ${signature}, not the PNG signature")
  endif()
  file(READ "${OUT}/${stem}.svg" svg)
  if(NOT svg MATCHES "^<\\?xml[^\n]*\n(<!DOCTYPE svg[^>]*>\n)?<svg [^>]*xmlns=\"http://www.w3.org/2000/svg\"" OR
     NOT svg MATCHES "</svg>\n?$")
    message(FATAL_ERROR "${OUT}/${stem}.svg is not an SVG document")
  endif()
endforeach()
