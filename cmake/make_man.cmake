# Build dembox.1 from the binary's own help texts (so the man page cannot
# drift from --help): cmake -DDEMBOX=path -DOUT=dembox.1 -DVERSION=x -P
foreach(cmd "" run sweep analyze plot bench examples example config)
  if(cmd STREQUAL "")
    execute_process(COMMAND ${DEMBOX} --help OUTPUT_VARIABLE text
                    RESULT_VARIABLE rc)
  else()
    execute_process(COMMAND ${DEMBOX} help ${cmd} OUTPUT_VARIABLE text
                    RESULT_VARIABLE rc)
  endif()
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "dembox help ${cmd} failed (${rc})")
  endif()
  # troff: a leading dot or quote would be a request; backslashes escape
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "(^|\n)([.'])" "\\1\\\\&\\2" text "${text}")
  if(cmd STREQUAL "")
    set(body "${body}.SH SYNOPSIS\n.nf\n${text}.fi\n")
  elseif(cmd STREQUAL "config")
    set(body "${body}.SH CONFIGURATION KEYS\n.nf\n${text}.fi\n")
  else()
    string(TOUPPER "${cmd}" up)
    set(body "${body}.SH ${up}\n.nf\n${text}.fi\n")
  endif()
endforeach()
file(WRITE ${OUT} ".TH DEMBOX 1 \"\" \"dembox ${VERSION}\" \"User Commands\"
.SH NAME
dembox \\- DEM laboratory for granular and powder element tests
${body}.SH FILES
Examples, outputs and the physics are documented in the docs/ folder of
the source tree; the library's API in dembox.h.
")
