#include "export/three_mf_writer.hpp"

#include <unistd.h>

#include <stdexcept>

#include <assimp/Exporter.hpp>
#include <assimp/scene.h>

#include "core/units.hpp"

namespace fibermold {

namespace {

/// A scene of one object with one mesh and a default material; the scene owns everything.
aiScene* scene_of(const SurfaceMesh& s, const std::string& name)
{
  auto* mesh = new aiMesh;
  mesh->mName = name;
  mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  mesh->mNumVertices = static_cast<unsigned>(s.num_vertices());
  mesh->mVertices = new aiVector3D[mesh->mNumVertices];
  for (Eigen::Index i = 0; i < s.num_vertices(); ++i) {
    const Eigen::Vector3d p = s.vertices.row(i) / units::mm;
    mesh->mVertices[i] =
        aiVector3D(static_cast<ai_real>(p.x()), static_cast<ai_real>(p.y()), static_cast<ai_real>(p.z()));
  }
  mesh->mNumFaces = static_cast<unsigned>(s.num_faces());
  mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (Eigen::Index f = 0; f < s.num_faces(); ++f) {
    aiFace& face = mesh->mFaces[f];
    face.mNumIndices = 3;
    face.mIndices = new unsigned[3];
    for (int c = 0; c < 3; ++c) face.mIndices[c] = static_cast<unsigned>(s.faces(f, c));
  }
  auto* scene = new aiScene;
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { mesh };
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial };
  // assimp's 3MF exporter writes the root node's children as objects, not the root's own meshes.
  auto* object = new aiNode(name);
  object->mNumMeshes = 1;
  object->mMeshes = new unsigned[1]{0};
  scene->mRootNode = new aiNode("root");
  scene->mRootNode->addChildren(1, &object);
  return scene;
}

} // namespace

void write_3mf(const std::filesystem::path& path, const SurfaceMesh& surface, const std::string& name)
{
  const std::unique_ptr<aiScene> scene(scene_of(surface, name));
  // The exporter zips straight into a file (it cannot export to memory): a temporary one, renamed.
  const std::filesystem::path temporary = path.string() + ".tmp-" + std::to_string(::getpid());
  Assimp::Exporter exporter;
  std::error_code error;
  if (exporter.Export(scene.get(), "3mf", temporary.string()) != AI_SUCCESS) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("writing " + path.string() +
                             ": assimp's 3MF exporter failed: " + exporter.GetErrorString());
  }
  std::filesystem::rename(temporary, path, error);
  if (error) {
    std::filesystem::remove(temporary, error);
    throw std::runtime_error("writing " + path.string() + ": cannot rename the finished file into place");
  }
}

} // namespace fibermold
