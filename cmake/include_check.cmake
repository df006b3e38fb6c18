# The layers' include check (CMakeLists.txt, "the layers' checks"), run with cmake -P:
#
#   cmake -DTABLE=<layers.cmake> -DSOURCE_DIR=<project> [-DSTAMP=<file>] -P include_check.cmake
#       every #include "FOLDER/..." in src/ must name the including file's own folder or that of a
#       layer its layer links, directly or through another; an include that runs up (or across, to
#       a layer not linked) is an error naming the file, the line and what the layer links
#   cmake -DTABLE=<layers.cmake> -DREADME=<README.md> -P include_check.cmake
#       the README's Layout table lists each layer with its folder and the layers it links as
#       CMakeLists.txt links them
#
# TABLE is written by CMakeLists.txt from the targets themselves: BELTSIM_LAYER_NAMES (each layer's
# name, also its folder under src/; "app" for the program), BELTSIM_LINKS_<name> (the layers it links
# directly) and BELTSIM_BELOW_<name> (every layer under it).
cmake_minimum_required(VERSION 3.22)
include(${TABLE})

if(DEFINED README)
  file(STRINGS ${README} lines ENCODING UTF-8)
  set(in_layout OFF)
  set(errors "")
  set(seen "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^## ")
      set(in_layout OFF)
      if(line STREQUAL "## Layout")
        set(in_layout ON)
      endif()
    endif()
    # | name | `src/folder/` | what it holds | links |
    if(in_layout AND line MATCHES "^\\| ([a-z]+) \\| `src/([a-z]+)/` \\|.*\\| ([^|]*) \\|$")
      set(name ${CMAKE_MATCH_1})
      set(folder ${CMAKE_MATCH_2})
      set(links_text ${CMAKE_MATCH_3})
      if(NOT name IN_LIST BELTSIM_LAYER_NAMES)
        string(APPEND errors "\n  ${README}: the Layout table lists \"${name}\", which is no layer")
        continue()
      endif()
      list(APPEND seen ${name})
      if(NOT folder STREQUAL name)
        string(APPEND errors "\n  ${README}: layer ${name}'s folder is src/${name}/, not src/${folder}/")
      endif()
      # the words of the links column that name layers, in the order CMakeLists.txt gives them
      string(REGEX MATCHALL "[a-z]+" words "${links_text}")
      set(listed "")
      foreach(w IN LISTS words)
        if(w IN_LIST BELTSIM_LAYER_NAMES)
          list(APPEND listed ${w})
        endif()
      endforeach()
      set(want ${BELTSIM_LINKS_${name}})
      list(SORT listed)
      list(SORT want)
      if(NOT "${listed}" STREQUAL "${want}")
        string(REPLACE ";" ", " want_text "${BELTSIM_LINKS_${name}}")
        string(APPEND errors "\n  ${README}: layer ${name} links \"${want_text}\" (CMakeLists.txt), "
                             "the Layout table says \"${links_text}\"")
      endif()
    endif()
  endforeach()
  foreach(name IN LISTS BELTSIM_LAYER_NAMES)
    if(NOT name IN_LIST seen)
      string(APPEND errors "\n  ${README}: the Layout table has no row for layer ${name} (src/${name}/)")
    endif()
  endforeach()
  if(errors)
    message(FATAL_ERROR "the README's layers disagree with CMakeLists.txt:${errors}")
  endif()
  return()
endif()

file(GLOB_RECURSE files RELATIVE ${SOURCE_DIR}/src ${SOURCE_DIR}/src/*.hpp ${SOURCE_DIR}/src/*.cpp
     ${SOURCE_DIR}/src/*.h ${SOURCE_DIR}/src/*.inc)
list(SORT files)
set(errors "")
foreach(file IN LISTS files)
  string(REGEX MATCH "^[^/]+" folder ${file})
  if(NOT folder IN_LIST BELTSIM_LAYER_NAMES)
    string(APPEND errors "\n  src/${file}: src/${folder}/ is the folder of no layer (CMakeLists.txt, beltsim_layer)")
    continue()
  endif()
  set(allowed ${folder} ${BELTSIM_BELOW_${folder}})
  file(STRINGS ${SOURCE_DIR}/src/${file} includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"[^\"/]+/")
  foreach(include IN LISTS includes)
    string(REGEX REPLACE "^[ \t]*#[ \t]*include[ \t]*\"([^\"/]+)/.*" "\\1" target "${include}")
    # only the folders of src/ are layers; "cvode/cvode.h" and the like are not ours
    if(target IN_LIST BELTSIM_LAYER_NAMES AND NOT target IN_LIST allowed)
      # the line number, for the message
      file(READ ${SOURCE_DIR}/src/${file} text)
      string(FIND "${text}" "${include}" at)
      string(SUBSTRING "${text}" 0 ${at} before)
      string(REGEX MATCHALL "\n" breaks "${before}")
      list(LENGTH breaks line)
      math(EXPR line "${line} + 1")
      string(REPLACE ";" ", " below "${BELTSIM_BELOW_${folder}}")
      if(NOT below)
        set(below "no layer")
      endif()
      string(STRIP "${include}" include)
      string(APPEND errors "\n  src/${file}:${line}: ${include}: layer ${folder} links ${below}, not ${target}")
    endif()
  endforeach()
endforeach()
if(errors)
  message(FATAL_ERROR "an include runs up or across the layers (README.md, Layout):${errors}")
endif()
if(DEFINED STAMP)
  file(TOUCH ${STAMP})
endif()
