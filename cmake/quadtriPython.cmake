# The Python module's interpreter and pybind11, and the QUADTRI_PYTHON switch (ON, OFF or AUTO:
# ON when both are found, re-decided at every configure; OFF under the sanitizers, whose
# runtime a plain interpreter does not load).
#
# Debian's pybind11, numpy and pytest are packages of the system interpreter, /usr/bin/python3,
# so it is preferred over whichever python3 comes first on PATH (pyenv, a virtual environment);
# -DPython_EXECUTABLE=... picks another.
set(QUADTRI_PYTHON AUTO CACHE STRING "Build the Python module (src/python/): ON, OFF or AUTO")
set_property(CACHE QUADTRI_PYTHON PROPERTY STRINGS AUTO ON OFF)
if(NOT QUADTRI_PYTHON STREQUAL "AUTO" AND NOT QUADTRI_PYTHON)
  return()
endif()
if(NOT Python_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The interpreter the Python module is for")
endif()
find_package(Python 3.8 COMPONENTS Interpreter Development.Module QUIET)
if(Python_FOUND)
  find_package(pybind11 2.6 CONFIG QUIET)
endif()
if(QUADTRI_PYTHON STREQUAL "AUTO")
  if(QUADTRI_SANITIZE OR QUADTRI_FUZZ)
    set(QUADTRI_PYTHON_ENABLED OFF)
    message(STATUS "quadtri: no Python module under the sanitizers")
  elseif(Python_FOUND AND pybind11_FOUND)
    set(QUADTRI_PYTHON_ENABLED ON)
  else()
    set(QUADTRI_PYTHON_ENABLED OFF)
    message(STATUS "quadtri: no Python module (needs Python 3 with its headers and pybind11: "
                   "Debian's python3-dev and pybind11-dev)")
  endif()
elseif(NOT (Python_FOUND AND pybind11_FOUND))
  message(FATAL_ERROR "QUADTRI_PYTHON=ON needs Python 3 with its headers and pybind11 (Debian: "
                      "python3-dev pybind11-dev); Python_EXECUTABLE is '${Python_EXECUTABLE}'")
else()
  set(QUADTRI_PYTHON_ENABLED ON)
endif()
if(QUADTRI_PYTHON_ENABLED)
  message(STATUS "quadtri: Python module for ${Python_EXECUTABLE} (${Python_VERSION}), "
                 "pybind11 ${pybind11_VERSION}")
endif()
