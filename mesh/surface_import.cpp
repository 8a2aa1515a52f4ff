#include "mesh/surface_import.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "core/atomic_file.hpp"
#include "core/input_error.hpp"
#include "core/units.hpp"

namespace fibermold {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void fail(const fs::path& file, const std::string& message)
{
  throw InputError(Diagnostic{file, 0, 0, "", message});
}

std::string lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// A PLY file whose header declares more elements than its body holds: assimp reads what is there
/// and the surface then fails a later check ("not closed") for a reason that is not the real one.
/// Lower bounds only: an ASCII element takes a line, a binary vertex at least three floats and a
/// binary face at least a count byte and three 1-byte indices.
std::optional<std::string> ply_truncation(const fs::path& file)
{
  std::ifstream in(file, std::ios::binary);
  std::string line, format;
  long long vertices = 0, faces = 0;
  for (int k = 0; k < 1000 && std::getline(in, line); ++k) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string word, name;
    long long count = 0;
    words >> word;
    if (word == "format") words >> format;
    if (word == "element" && words >> name >> count)
      (name == "vertex" ? vertices : name == "face" ? faces : count) = count;
    if (word == "end_header") break;
  }
  const auto header_end = static_cast<double>(in.tellg());
  if (line.rfind("end_header", 0) != 0 || vertices < 0 || faces < 0 || header_end < 0)
    return std::nullopt; // assimp judges the header
  const auto size = static_cast<double>(fs::file_size(file));
  const double elements = static_cast<double>(vertices) + static_cast<double>(faces);
  const double least_bytes =
      12.0 * static_cast<double>(vertices) + 4.0 * static_cast<double>(faces); // no overflow near 2^63
  if (format == "ascii") {
    long long lines = 0;
    while (std::getline(in, line) && static_cast<double>(lines) < elements)
      if (line.find_first_not_of(" \t\r") != std::string::npos) ++lines;
    if (static_cast<double>(lines) < elements)
      return fmt::format(
          "its header declares {} vertices and {} faces, but {} lines of data follow: the file is truncated or its "
          "header is wrong",
          vertices, faces, lines);
  } else if (size - header_end < least_bytes) {
    return fmt::format("its header declares {} vertices and {} faces, which need at least {:.0f} bytes, but {:.0f} "
                       "follow: the file is "
                       "truncated or its header is wrong",
                       vertices, faces, least_bytes, size - header_end);
  }
  return std::nullopt;
}

} // namespace

std::vector<fs::path> surface_files(const fs::path& file)
{
  std::vector<fs::path> files{file};
  if (lower(file.extension().string()) != ".gltf") return files;
  try {
    const nlohmann::json gltf = nlohmann::json::parse(read_file(file));
    for (const char* section : {"buffers", "images"})
      if (gltf.contains(section))
        for (const auto& item : gltf[section])
          if (item.contains("uri") && item["uri"].is_string()) {
            const std::string uri = item["uri"];
            if (!uri.starts_with("data:")) files.push_back((file.parent_path() / uri).lexically_normal());
          }
  } catch (const std::exception&) {
    // Unreadable JSON: the import itself reports it.
  }
  std::error_code ec;
  std::erase_if(files, [&](const fs::path& p) { return p != file && !fs::is_regular_file(p, ec); });
  return files;
}

std::vector<std::string> supported_surface_extensions()
{
  Assimp::Importer importer;
  std::string list; // "*.3d;*.3ds;..."
  importer.GetExtensionList(list);
  std::vector<std::string> extensions;
  std::size_t start = 0;
  while (start < list.size()) {
    std::size_t end = list.find(';', start);
    if (end == std::string::npos) end = list.size();
    std::string e = list.substr(start, end - start);
    if (e.starts_with("*")) e.erase(0, 1);
    if (!e.empty()) extensions.push_back(lower(e));
    start = end + 1;
  }
  return extensions;
}

SurfaceMesh import_surface(const fs::path& file, double metres_per_unit)
{
  std::error_code ec;
  if (!fs::exists(file, ec)) fail(file, "surface file not found");
  if (!fs::is_regular_file(file, ec)) fail(file, "surface is not a regular file");
  if (fs::file_size(file, ec) == 0) fail(file, "surface file is empty");
  const std::string extension = lower(file.extension().string());
  Assimp::Importer importer;
  if (extension.empty() || !importer.IsExtensionSupported(extension)) {
    fail(file, fmt::format("unsupported surface format '{}'; use one of: .stl .obj .ply .off .3mf .gltf .glb "
                           "(and the other formats assimp reads)",
                           extension));
  }
  // Keep only positions: normals and texture coordinates would stop identical positions from welding.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TEXCOORDS | aiComponent_COLORS |
                                                          aiComponent_TANGENTS_AND_BITANGENTS);
  // ValidateDataStructure runs first and rejects out-of-range indices before anything uses them.
  const unsigned flags = aiProcess_ValidateDataStructure | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                         aiProcess_DropNormals | aiProcess_RemoveComponent | aiProcess_PreTransformVertices;
  if (extension == ".ply")
    if (const auto truncated = ply_truncation(file)) fail(file, "cannot read the surface: " + *truncated);
  const aiScene* scene = importer.ReadFile(file.string(), flags);
  if (!scene) {
    std::string why = importer.GetErrorString();
    for (const std::string& named : {" for " + file.string(), file.string()}) // the message names the file already
      if (const auto at = why.find(named); at != std::string::npos) why.erase(at, named.size());
    while (!why.empty() && (why.back() == '.' || why.back() == ' ' || why.back() == '\n')) why.pop_back();
    fail(file,
         fmt::format("cannot read the surface ({}): the file is damaged, truncated or in another format (assimp: {})",
                     extension, why));
  }

  // Merge all meshes, welding vertices with identical coordinates across them.
  std::map<std::array<double, 3>, int> index_of;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> faces;
  std::size_t non_triangles = 0, non_finite = 0;
  Eigen::Vector3d first_non_finite = Eigen::Vector3d::Zero();
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    std::vector<int> local(mesh->mNumVertices);
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D& p = mesh->mVertices[v];
      const std::array<double, 3> key{p.x, p.y, p.z};
      if (!std::isfinite(key[0]) || !std::isfinite(key[1]) || !std::isfinite(key[2])) {
        if (non_finite++ == 0) first_non_finite = {key[0], key[1], key[2]};
        local[v] = 0;
        continue;
      }
      auto [it, inserted] = index_of.emplace(key, static_cast<int>(vertices.size()));
      if (inserted) vertices.emplace_back(key[0], key[1], key[2]);
      local[v] = it->second;
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices != 3) {
        ++non_triangles;
        continue;
      }
      for (unsigned k = 0; k < 3; ++k)
        if (face.mIndices[k] >= mesh->mNumVertices)
          fail(file, fmt::format("face {} refers to vertex {}, but there are {} vertices", f, face.mIndices[k],
                                 mesh->mNumVertices));
      faces.emplace_back(local[face.mIndices[0]], local[face.mIndices[1]], local[face.mIndices[2]]);
    }
  }
  if (non_finite > 0)
    fail(file, fmt::format("{} vertices have coordinates that are not finite numbers, e.g. ({}, {}, {})", non_finite,
                           first_non_finite.x(), first_non_finite.y(), first_non_finite.z()));
  if (faces.empty()) fail(file, "the surface has no triangles");
  if (non_triangles > 0)
    fail(file, fmt::format("the surface has {} point or line elements; only a closed triangle surface can be meshed",
                           non_triangles));

  // A body between 0.1 mm and 10 m across: anything else is a unit mistake or a damaged file.
  Eigen::Vector3d lo = vertices.front(), hi = vertices.front();
  for (const Eigen::Vector3d& v : vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double span = (hi - lo).norm() * metres_per_unit;
  if (!(span >= kMinBodySize && span <= kMaxBodySize))
    fail(file,
         fmt::format(
             "the surface spans {:.3g} mm corner to corner ({:.3g} to {:.3g} in the file's units): a body is between "
             "{} mm and {} m across; check [design].units",
             span / units::mm, lo.minCoeff(), hi.maxCoeff(), kMinBodySize / units::mm, kMaxBodySize));

  SurfaceMesh surface;
  surface.source = file;
  surface.vertices.resize(static_cast<Eigen::Index>(vertices.size()), 3);
  surface.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t i = 0; i < vertices.size(); ++i)
    surface.vertices.row(static_cast<Eigen::Index>(i)) = vertices[i].transpose() * metres_per_unit;
  for (std::size_t i = 0; i < faces.size(); ++i) surface.faces.row(static_cast<Eigen::Index>(i)) = faces[i].transpose();
  return surface;
}

} // namespace fibermold
