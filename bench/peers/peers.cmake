# Peers of `pronk bench` (docs/performance.md): separate executables, built only when their
# Debian packages are installed (scripts/setup.sh installs them). `pronk bench` runs the ones it finds beside itself and
# merges their JSON output; without them it reports them as unavailable.

# SUNDIALS CVODE 6.x (libsundials-dev): plain find_library, because the package's
# CMake config drags in PETSc, hypre and MPI targets that the peer does not need.
find_path(PRONK_CVODE_INCLUDE_DIR cvode/cvode.h)
find_library(PRONK_CVODE_LIB sundials_cvode)
find_library(PRONK_NVECSERIAL_LIB sundials_nvecserial)
find_library(PRONK_SUNMATDENSE_LIB sundials_sunmatrixdense)
find_library(PRONK_SUNLSDENSE_LIB sundials_sunlinsoldense)
find_library(PRONK_SUNMATSPARSE_LIB sundials_sunmatrixsparse)
find_library(PRONK_SUNLSKLU_LIB sundials_sunlinsolklu)
find_path(PRONK_KLU_INCLUDE_DIR klu.h PATH_SUFFIXES suitesparse)
if(PRONK_CVODE_INCLUDE_DIR AND PRONK_CVODE_LIB AND PRONK_NVECSERIAL_LIB AND PRONK_SUNMATDENSE_LIB
   AND PRONK_SUNLSDENSE_LIB)
  message(STATUS "pronk bench peer: SUNDIALS CVODE found (${PRONK_CVODE_LIB})")
  add_executable(pronk_peer_cvode bench/peers/cvode_peer.cpp)
  target_link_libraries(pronk_peer_cvode PRIVATE pronk_lib ${PRONK_CVODE_LIB} ${PRONK_NVECSERIAL_LIB}
                        ${PRONK_SUNMATDENSE_LIB} ${PRONK_SUNLSDENSE_LIB})
  target_include_directories(pronk_peer_cvode PRIVATE ${PRONK_CVODE_INCLUDE_DIR})
  if(PRONK_SUNMATSPARSE_LIB AND PRONK_SUNLSKLU_LIB AND PRONK_KLU_INCLUDE_DIR)
    target_link_libraries(pronk_peer_cvode PRIVATE ${PRONK_SUNMATSPARSE_LIB} ${PRONK_SUNLSKLU_LIB})
    target_include_directories(pronk_peer_cvode PRIVATE ${PRONK_KLU_INCLUDE_DIR})
    target_compile_definitions(pronk_peer_cvode PRIVATE PRONK_CVODE_KLU=1)
  endif()
else()
  message(STATUS "pronk bench peer: SUNDIALS CVODE not found (optional; libsundials-dev)")
endif()

# MuJoCo 2.2 (libmujoco-dev; found in CMakeLists.txt).
if(PRONK_HAVE_MUJOCO)
  message(STATUS "pronk bench peer: MuJoCo found (${PRONK_MUJOCO_LIB})")
  add_executable(pronk_peer_mujoco bench/peers/mujoco_peer.cpp)
  target_link_libraries(pronk_peer_mujoco PRIVATE ${PRONK_MUJOCO_LIB} nlohmann_json::nlohmann_json)
  target_include_directories(pronk_peer_mujoco PRIVATE ${PRONK_MUJOCO_INCLUDE_DIR})
else()
  message(STATUS "pronk bench peer: MuJoCo not used (optional; libmujoco-dev)")
endif()
