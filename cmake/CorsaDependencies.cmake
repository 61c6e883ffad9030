# Finds every third-party library, all from Debian 12 packages (scripts/setup installs them).
# A missing one stops configuration with the Debian package to install.

function(corsa_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR "Corsa needs ${what}: install the Debian package '${package}' "
                        "(or run scripts/setup as root, which installs everything).")
  endif()
endfunction()

# A Python module the interpreter must import at run time (not built against): checked here so
# that a missing package is named before anything is built.
function(corsa_require_python_module module package)
  execute_process(COMMAND ${Python3_EXECUTABLE} -c "import ${module}"
                  RESULT_VARIABLE corsa_import_failed OUTPUT_QUIET ERROR_QUIET)
  if(corsa_import_failed)
    set(corsa_python_module_found FALSE)
  else()
    set(corsa_python_module_found TRUE)
  endif()
  corsa_require(corsa_python_module_found "${module} for ${Python3_EXECUTABLE}" ${package})
endfunction()

find_package(Threads REQUIRED)

find_package(tinyxml2 CONFIG QUIET)
corsa_require(tinyxml2_FOUND "tinyxml2" libtinyxml2-dev)

find_package(nlohmann_json 3 CONFIG QUIET)
corsa_require(nlohmann_json_FOUND "nlohmann-json" nlohmann-json3-dev)

find_package(Eigen3 3.3 CONFIG QUIET)
corsa_require(Eigen3_FOUND "Eigen 3" libeigen3-dev)

find_package(embree 3 CONFIG QUIET)
corsa_require(embree_FOUND "Embree 3" libembree-dev)

find_package(assimp CONFIG QUIET)
corsa_require(assimp_FOUND "assimp" libassimp-dev)

find_package(PROJ CONFIG QUIET)
corsa_require(PROJ_FOUND "PROJ" libproj-dev)

find_package(TBB CONFIG QUIET)
corsa_require(TBB_FOUND "oneTBB" libtbb-dev)

# shapelib ships only a pkg-config file on Debian.
find_path(SHAPELIB_INCLUDE_DIR shapefil.h)
find_library(SHAPELIB_LIBRARY NAMES shp)
if(SHAPELIB_INCLUDE_DIR AND SHAPELIB_LIBRARY)
  set(SHAPELIB_FOUND TRUE)
  add_library(corsa::shapelib UNKNOWN IMPORTED)
  set_target_properties(corsa::shapelib PROPERTIES
    IMPORTED_LOCATION "${SHAPELIB_LIBRARY}" INTERFACE_INCLUDE_DIRECTORIES "${SHAPELIB_INCLUDE_DIR}")
endif()
corsa_require(SHAPELIB_FOUND "shapelib" libshp-dev)

# OpenCV: only the four modules we use (the full libopencv-dev pulls ~100 more packages and its
# CMake config insists on all of them), so the libraries are found directly.
find_path(OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
corsa_require(OPENCV_INCLUDE_DIR "OpenCV headers" libopencv-core-dev)
add_library(corsa::opencv INTERFACE IMPORTED)
set_target_properties(corsa::opencv PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${OPENCV_INCLUDE_DIR}")
foreach(module core imgproc imgcodecs videoio)
  find_library(OPENCV_${module}_LIBRARY NAMES opencv_${module})
  corsa_require(OPENCV_${module}_LIBRARY "OpenCV ${module}" libopencv-${module}-dev)
  target_link_libraries(corsa::opencv INTERFACE "${OPENCV_${module}_LIBRARY}")
endforeach()

# libdeflate: the dataset's PNG files are deflated with it (sensors/src/png_codec.cpp).
find_path(LIBDEFLATE_INCLUDE_DIR libdeflate.h)
find_library(LIBDEFLATE_LIBRARY NAMES deflate)
if(LIBDEFLATE_INCLUDE_DIR AND LIBDEFLATE_LIBRARY)
  set(LIBDEFLATE_FOUND TRUE)
  add_library(corsa::libdeflate UNKNOWN IMPORTED)
  set_target_properties(corsa::libdeflate PROPERTIES
    IMPORTED_LOCATION "${LIBDEFLATE_LIBRARY}" INTERFACE_INCLUDE_DIRECTORIES "${LIBDEFLATE_INCLUDE_DIR}")
endif()
corsa_require(LIBDEFLATE_FOUND "libdeflate" libdeflate-dev)

# FFmpeg's libraries: the preview video is encoded with libx264 through them
# (sensors/src/h264_writer.cpp). OpenCV's videoio is built on the same libraries.
add_library(corsa::ffmpeg INTERFACE IMPORTED)
foreach(ffmpeg_lib avcodec avformat avutil swscale)
  string(TOUPPER ${ffmpeg_lib} ffmpeg_upper)
  find_path(${ffmpeg_upper}_INCLUDE_DIR lib${ffmpeg_lib}/version.h)
  find_library(${ffmpeg_upper}_LIBRARY NAMES ${ffmpeg_lib})
  corsa_require(${ffmpeg_upper}_LIBRARY "FFmpeg's lib${ffmpeg_lib}" lib${ffmpeg_lib}-dev)
  corsa_require(${ffmpeg_upper}_INCLUDE_DIR "FFmpeg's lib${ffmpeg_lib} headers" lib${ffmpeg_lib}-dev)
  target_include_directories(corsa::ffmpeg INTERFACE "${${ffmpeg_upper}_INCLUDE_DIR}")
  target_link_libraries(corsa::ffmpeg INTERFACE "${${ffmpeg_upper}_LIBRARY}")
endforeach()

# SUNDIALS: CVODE with the serial vector and the dense linear solver; ARKODE (explicit
# Runge-Kutta) for the vehicle dynamics of the engine's `dynamics` controller.
find_path(SUNDIALS_INCLUDE_DIR cvode/cvode.h)
find_library(SUNDIALS_CVODE_LIBRARY NAMES sundials_cvode)
find_library(SUNDIALS_ARKODE_LIBRARY NAMES sundials_arkode)
find_library(SUNDIALS_NVEC_LIBRARY NAMES sundials_nvecserial)
# An executable links the static archives (libsundials-dev ships them, position-independent):
# two fewer shared objects to map and relocate at every start of `corsa`, whose ~1,100 symbol
# relocations cost more than a short run's integration. Shared objects (the plugin, the Python
# module) link the shared libraries.
find_library(SUNDIALS_CVODE_ARCHIVE NAMES libsundials_cvode.a)
find_library(SUNDIALS_ARKODE_ARCHIVE NAMES libsundials_arkode.a)
find_library(SUNDIALS_NVEC_ARCHIVE NAMES libsundials_nvecserial.a)
if(SUNDIALS_INCLUDE_DIR AND SUNDIALS_CVODE_LIBRARY AND SUNDIALS_ARKODE_LIBRARY
   AND SUNDIALS_NVEC_LIBRARY AND SUNDIALS_CVODE_ARCHIVE AND SUNDIALS_ARKODE_ARCHIVE
   AND SUNDIALS_NVEC_ARCHIVE)
  set(SUNDIALS_FOUND TRUE)
  set(sundials_shared "${SUNDIALS_CVODE_LIBRARY};${SUNDIALS_ARKODE_LIBRARY};${SUNDIALS_NVEC_LIBRARY}")
  set(sundials_static "${SUNDIALS_CVODE_ARCHIVE};${SUNDIALS_ARKODE_ARCHIVE};${SUNDIALS_NVEC_ARCHIVE}")
  add_library(corsa::sundials INTERFACE IMPORTED)
  # $<TARGET_PROPERTY:TYPE> is the type of the target being linked, not of the module library.
  set_target_properties(corsa::sundials PROPERTIES
    INTERFACE_INCLUDE_DIRECTORIES "${SUNDIALS_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES
      "$<IF:$<STREQUAL:$<TARGET_PROPERTY:TYPE>,EXECUTABLE>,${sundials_static},${sundials_shared}>")
endif()
corsa_require(SUNDIALS_FOUND "SUNDIALS (CVODE, ARKODE)" libsundials-dev)

# Debian's interpreter, into which python3-numpy and python3-pytest install, even when another
# python3 (pyenv, a virtualenv) comes first on PATH; -DPython3_EXECUTABLE=... chooses another.
if(NOT DEFINED Python3_EXECUTABLE AND EXISTS /usr/bin/python3)
  set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "Python interpreter (module, tests)")
endif()

if(CORSA_BUILD_PYTHON)
  find_package(Python3 COMPONENTS Interpreter Development.Module QUIET)
  corsa_require(Python3_Development.Module_FOUND "the Python 3 headers" python3-dev)
  find_package(pybind11 CONFIG QUIET)
  corsa_require(pybind11_FOUND "pybind11" pybind11-dev)
  # The module imports numpy at run time (states(), sensor frames, datasets).
  corsa_require_python_module(numpy python3-numpy)
  if(CORSA_BUILD_TESTS)
    corsa_require_python_module(pytest python3-pytest)
  endif()
endif()

if(CORSA_BUILD_TESTS)
  find_package(Catch2 2 CONFIG QUIET)
  corsa_require(Catch2_FOUND "Catch2 v2" catch2)
  # The module layering check (tests/layering) is a Python script.
  find_package(Python3 COMPONENTS Interpreter QUIET)
  corsa_require(Python3_Interpreter_FOUND "Python 3" python3)
  # tests/cluster starts a single-node Slurm (slurmctld, slurmd) authenticated by munge.
  find_program(CORSA_SLURMCTLD slurmctld PATHS /usr/sbin)
  find_program(CORSA_SLURMD slurmd PATHS /usr/sbin)
  find_program(CORSA_MUNGED munged PATHS /usr/sbin)
  corsa_require(CORSA_SLURMCTLD "slurmctld" slurm-wlm)
  corsa_require(CORSA_SLURMD "slurmd" slurm-wlm)
  corsa_require(CORSA_MUNGED "munged" munge)
  # xmllint validates every .xodr Corsa writes against the ASAM OpenDRIVE 1.7 XSD (tests/xsd).
  find_program(CORSA_XMLLINT xmllint)
  corsa_require(CORSA_XMLLINT "xmllint" libxml2-utils)
endif()

if(CORSA_BUILD_BENCH)
  find_package(benchmark CONFIG QUIET)
  corsa_require(benchmark_FOUND "Google Benchmark" libbenchmark-dev)
  # The pedestrian benchmark measures OpenCV's HOG people detector on rendered frames.
  find_library(OPENCV_objdetect_LIBRARY NAMES opencv_objdetect)
  find_path(OPENCV_OBJDETECT_INCLUDE opencv2/objdetect.hpp PATH_SUFFIXES opencv4)
  corsa_require(OPENCV_objdetect_LIBRARY "OpenCV objdetect" libopencv-objdetect-dev)
  corsa_require(OPENCV_OBJDETECT_INCLUDE "OpenCV objdetect headers" libopencv-objdetect-dev)
  add_library(corsa::opencv_objdetect INTERFACE IMPORTED)
  target_link_libraries(corsa::opencv_objdetect INTERFACE "${OPENCV_objdetect_LIBRARY}")
endif()
