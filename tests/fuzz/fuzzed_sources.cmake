# The library sources the fuzzed readers need, and nothing more: the fuzz targets compile these
# alone with the fuzzer's instrumentation (tests/fuzz/CMakeLists.txt, a minute instead of half
# an hour), and the normal build's fuzz_replay test links the same list (tests/CMakeLists.txt), so
# that a reader that comes to need another library file fails to link in every build, not only
# in ./kerf.sh fuzz.
set(kerf_fuzzed_sources
  ${PROJECT_SOURCE_DIR}/common/src/cut/blade_path.cpp
  ${PROJECT_SOURCE_DIR}/common/src/fem/tet_quadrature.cpp
  ${PROJECT_SOURCE_DIR}/common/src/fem/tet_shape_functions.cpp
  ${PROJECT_SOURCE_DIR}/common/src/fem/tet_shape_gradients.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/check_tet_mesh.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/check_triangle_surface.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/node_region.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/number_table_csv.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/parse_obj.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/parse_off.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/parse_stl.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_gmsh.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_medit.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_mesh.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_surface.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_vtk.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/read_vtk_triangles.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/vtk_legacy_mesh_part.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/vtk_reader_checks.cpp
  ${PROJECT_SOURCE_DIR}/common/src/mesh/vtu_counts.cpp
  ${PROJECT_SOURCE_DIR}/common/src/scene/displacement_file.cpp
  ${PROJECT_SOURCE_DIR}/common/src/scene/scene.cpp
  ${PROJECT_SOURCE_DIR}/common/src/solve/cholmod_ordering.cpp)
