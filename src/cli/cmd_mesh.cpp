// `quadtri mesh NAME [params] -o FILE`: writes a built-in shape.
#include <fmt/core.h>
#include <fmt/ranges.h>

#include "commands.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"

namespace quadtri::cli {

Action addMeshCommand(CLI::App& app) {
  struct Options {
    std::string name, output, normals = "analytic";
    ShapeParams params;
    std::vector<double> radii;
    double creaseAngleDeg = kDefaultCreaseAngleDeg;
  };
  auto opt = std::make_shared<Options>();
  CLI::App* sub = app.add_subcommand("mesh", "Write a built-in shape as OBJ or PLY");
  sub->add_option("name", opt->name, "Shape")
      ->required()
      ->check(CLI::IsMember(builtinShapeNames()));
  sub->add_option("-o,--output", opt->output, "Output file (.obj or .ply)")
      ->required()
      ->check(outputFile());
  sub->add_option("--level", opt->params.level, "Icosphere/ellipsoid subdivision level")
      ->capture_default_str();
  sub->add_option("--segments", opt->params.segments,
                  "uv-sphere/torus/cylinder divisions around the axis")
      ->capture_default_str();
  sub->add_option("--rings", opt->params.rings,
                  "uv-sphere/torus divisions along the profile, cylinder along its height")
      ->capture_default_str();
  sub->add_option("--divisions", opt->params.divisions, "cube: divisions of each edge")
      ->capture_default_str();
  sub->add_option("--radii", opt->radii, "Ellipsoid semi-axes a b c")->expected(3);
  sub->add_option("--major", opt->params.major, "Torus major radius")->capture_default_str();
  sub->add_option("--minor", opt->params.minor, "Torus minor radius")->capture_default_str();
  sub->add_option("--cells", opt->params.cells,
                  "genus2: marching-tetrahedra grid cells along the shape's length")
      ->capture_default_str();
  sub->add_option("--normals", opt->normals,
                  "Vertex normals: analytic (true surface; split at the cube's and cylinder's "
                  "creases), average (thesis eq. 2.8) or angle (angle-weighted, split at "
                  "--crease-angle)")
      ->check(CLI::IsMember({"analytic", "average", "angle"}))
      ->capture_default_str();
  CLI::Option* crease = sub->add_option(
      "--crease-angle", opt->creaseAngleDeg,
      fmt::format("Degrees: with --normals angle, faces meeting at more than this get split "
                  "normals (180: never; default {:g})",
                  kDefaultCreaseAngleDeg));
  return [opt, crease]() {
    if (crease->count() > 0 && opt->normals != "angle")
      fail("--crease-angle applies to --normals angle, not to --normals {}", opt->normals);
    if (opt->radii.size() == 3)
      opt->params.radii = Vec3(opt->radii[0], opt->radii[1], opt->radii[2]);
    opt->params.analyticNormals = opt->normals == "analytic";
    BuiltinMesh b = makeBuiltin(opt->name, opt->params);
    if (opt->normals == "angle") computeCreaseNormals(b.mesh, opt->creaseAngleDeg);
    saveMesh(b.mesh, opt->output);
    fmt::print("{}: {} ({} vertices, {} triangles)\n", opt->output, b.description,
               b.mesh.positions.size(), b.mesh.triangleCount());
    return 0;
  };
}

}  // namespace quadtri::cli
