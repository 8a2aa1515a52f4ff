#include "mesh/surface_import.hpp"

#include <fstream>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "export/stl_writer.hpp"
#include "mesh/surface_check.hpp"
#include "primitives.hpp"
#include "test_support.hpp"

namespace fibermold {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

/// The InputError message of importing `path`.
std::string import_error(const fs::path& path)
{
  try {
    import_surface(path, 1e-3);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected an InputError for " << path;
  return "";
}

class SurfaceImport : public ::testing::Test {
protected:
  test::TempDir dir_;
  const SurfaceMesh torus_ = test::torus(0.03, 0.01, 20, 10);
  const double volume_ = signed_volume(torus_);
};

TEST_F(SurfaceImport, EveryFormatGivesTheSameWeldedSurface)
{
  write_stl(dir_ / "binary.stl", torus_);
  test::write_ascii_stl(dir_ / "ascii.stl", torus_);
  test::write_obj(dir_ / "mesh.obj", torus_);
  test::write_off(dir_ / "mesh.off", torus_);
  test::write_ply(dir_ / "mesh.ply", torus_);
  for (const char* name : {"binary.stl", "ascii.stl", "mesh.obj", "mesh.off", "mesh.ply"}) {
    SCOPED_TRACE(name);
    const SurfaceMesh s = import_surface(dir_ / name, 1e-3);
    EXPECT_EQ(s.num_vertices(), torus_.num_vertices()); // STL's per-face vertices are welded
    EXPECT_EQ(s.num_faces(), torus_.num_faces());
    EXPECT_NEAR(signed_volume(s), volume_, 1e-6 * volume_);
    EXPECT_TRUE(check_surface(s).ok());
  }
}

TEST_F(SurfaceImport, UnitsScaleTheCoordinates)
{
  test::write_obj(dir_ / "cm.obj", torus_, 100.0); // written in cm
  const SurfaceMesh s = import_surface(dir_ / "cm.obj", 1e-2);
  EXPECT_NEAR(s.vertices.col(0).maxCoeff(), torus_.vertices.col(0).maxCoeff(), 1e-9);
}

TEST_F(SurfaceImport, MissingFile)
{
  EXPECT_THAT(import_error(dir_ / "nope.stl"), HasSubstr("nope.stl: surface file not found"));
}

TEST_F(SurfaceImport, EmptyFile)
{
  test::write_text(dir_ / "empty.stl", "");
  EXPECT_THAT(import_error(dir_ / "empty.stl"), HasSubstr("empty.stl: surface file is empty"));
}

TEST_F(SurfaceImport, RandomBytes)
{
  std::mt19937 random(7);
  std::string bytes(4093, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  test::write_text(dir_ / "noise.stl", bytes);
  EXPECT_THAT(import_error(dir_ / "noise.stl"), HasSubstr("noise.stl: cannot read the surface"));
}

TEST_F(SurfaceImport, UnsupportedExtension)
{
  test::write_text(dir_ / "body.scad", "cube(10);");
  EXPECT_THAT(import_error(dir_ / "body.scad"), HasSubstr("unsupported surface format '.scad'"));
}

TEST_F(SurfaceImport, FaceIndexOutOfRange)
{
  test::write_text(dir_ / "oob.ply",
                   "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                   "property float z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                   "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 99999\n");
  EXPECT_THAT(import_error(dir_ / "oob.ply"), HasSubstr("oob.ply: "));
}

TEST_F(SurfaceImport, NanCoordinates)
{
  SurfaceMesh s = test::box({0, 0, 0}, {0.01, 0.01, 0.01}, 1);
  s.vertices(3, 1) = std::nan("");
  test::write_obj(dir_ / "nan.obj", s);
  EXPECT_THAT(import_error(dir_ / "nan.obj"), HasSubstr("not finite"));
}

} // namespace
} // namespace fibermold
