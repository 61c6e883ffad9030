#include "corsa/sensors/model_io.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <cmath>
#include <map>

#include "corsa/core/atomic_file.h"
#include "corsa/core/diagnostic.h"
#include "corsa/core/strings.h"
#include "corsa/sensors/georeference.h"
#include "corsa/sensors/texture_image.h"

namespace corsa::sensors {
namespace {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& message) {
  throw InputError(make_error(path.string(), 0, message));
}

/// Maps model coordinates (after the up-axis fix) to map coordinates.
class Placer {
 public:
  Placer(const std::filesystem::path& path, const ModelPlacement& p) : p_(p) {
    if (!p.model_crs.empty() && !p.map_crs.empty() && p.model_crs != p.map_crs) {
      try {
        crs_.emplace(p.model_crs, p.map_crs);
      } catch (const InputError& error) {
        fail(path, error.diagnostic().message);
      }
    }
    if (p.anchor) {
      anchor_ = crs_ ? crs_->apply(*p.anchor) : *p.anchor;
      if (crs_) {
        // Grid convergence: the angle between grid north and true north at the anchor.
        const double step = crs_->source_is_geographic() ? 1e-4 : 10.0;
        const Vec3 north = crs_->apply(*p.anchor + Vec3{0.0, step, 0.0});
        convergence_ = std::atan2(-(north.x - anchor_.x), north.y - anchor_.y);
      }
    }
    const double c = std::cos(p.heading + convergence_);
    const double s = std::sin(p.heading + convergence_);
    cos_ = c * p.scale;
    sin_ = s * p.scale;
  }

  Vec3 place(Vec3 v) const {
    const Vec3 r{cos_ * v.x - sin_ * v.y, sin_ * v.x + cos_ * v.y, p_.scale * v.z};
    if (p_.anchor) {
      return anchor_ + r + p_.offset;
    }
    return (crs_ ? crs_->apply(r) : r) + p_.offset;
  }

 private:
  const ModelPlacement& p_;
  std::optional<CrsTransform> crs_;
  Vec3 anchor_;
  double convergence_ = 0.0;
  double cos_ = 1.0, sin_ = 0.0;
};

bool y_up_for(const std::filesystem::path& path, UpAxis axis) {
  if (axis != UpAxis::kAuto) {
    return axis == UpAxis::kY;
  }
  const std::string ext = to_lower(path.extension().string());
  return ext == ".gltf" || ext == ".glb";
}

/// The model's materials: base colour, metallic/roughness, opacity and emission (glTF PBR
/// keys where present, the classic diffuse ones otherwise) and the base-colour texture (a file
/// beside the model or one embedded in it). A texture that cannot be read is a warning and the
/// material keeps its colour.
struct MaterialReader {
  const aiScene* scene;
  std::filesystem::path model;
  Diagnostics* diagnostics;
  std::map<std::string, std::shared_ptr<const TextureImage>> textures;

  std::shared_ptr<const TextureImage> texture(const std::string& ref) {
    const auto it = textures.find(ref);
    if (it != textures.end()) {
      return it->second;
    }
    std::shared_ptr<const TextureImage> image;
    try {
      if (!ref.empty() && ref[0] == '*') {
        const auto index = parse_int(ref.substr(1));
        if (!index || *index < 0 || *index >= static_cast<int64_t>(scene->mNumTextures)) {
          throw InputError(make_error(model.string(), 0, "no embedded texture " + ref));
        }
        const aiTexture* t = scene->mTextures[*index];
        if (t->mHeight == 0) {  // compressed (PNG, JPEG) bytes
          image = TextureImage::decode(
              std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(t->pcData), t->mWidth),
              model.string() + ":" + ref);
        } else {
          std::vector<uint8_t> rgba;
          for (unsigned i = 0; i < t->mWidth * t->mHeight; ++i) {
            rgba.insert(rgba.end(),
                        {t->pcData[i].r, t->pcData[i].g, t->pcData[i].b, t->pcData[i].a});
          }
          image =
              TextureImage::from_srgb8(static_cast<int>(t->mWidth), static_cast<int>(t->mHeight), 4,
                                       rgba, model.string() + ":" + ref);
        }
      } else {
        image = TextureImage::load(model.parent_path() / ref);
      }
    } catch (const InputError& error) {
      if (diagnostics != nullptr) {
        diagnostics->add_once(
            "model-texture:" + model.string() + ":" + ref,
            make_warning(model.string(), 0,
                         "texture '" + ref + "' cannot be read (" + error.diagnostic().message +
                             "); the material's colour is used instead"));
      }
    }
    textures[ref] = image;
    return image;
  }

  /// The material of a mesh; `textured` tells whether it has a texture (or PBR factors) worth
  /// a material of its own rather than a plain colour.
  Material read(unsigned index, bool& textured) {
    const aiMaterial* m = scene->mMaterials[index];
    Material out;
    aiString name;
    out.name = model.filename().string() + ":" +
               (m->Get(AI_MATKEY_NAME, name) == AI_SUCCESS ? std::string(name.C_Str())
                                                           : std::to_string(index));
    aiColor4D c;
    if (m->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS ||
        m->Get(AI_MATKEY_COLOR_DIFFUSE, c) == AI_SUCCESS) {
      // Model colours are sRGB-encoded (glTF's base colour factor is linear; assimp 5.2 reports
      // it as read, so glTF colours are taken as linear).
      const bool gltf = to_lower(model.extension().string()).rfind(".gl", 0) == 0;
      out.base_color = gltf ? Color{c.r, c.g, c.b}
                            : Color{std::pow(std::clamp(c.r, 0.0f, 1.0f), 2.2f),
                                    std::pow(std::clamp(c.g, 0.0f, 1.0f), 2.2f),
                                    std::pow(std::clamp(c.b, 0.0f, 1.0f), 2.2f)};
    }
    float f = 0.0f;
    textured = false;
    // Plain dielectrics keep the colour-only path (untextured buildings get a facade); metals,
    // glass, lamps and textured materials get a material of their own.
    if (m->Get(AI_MATKEY_METALLIC_FACTOR, f) == AI_SUCCESS) {
      out.metallic = std::clamp(static_cast<double>(f), 0.0, 1.0);
      textured = textured || out.metallic > 0.05;
    }
    if (m->Get(AI_MATKEY_ROUGHNESS_FACTOR, f) == AI_SUCCESS) {
      out.roughness = std::clamp(static_cast<double>(f), 0.0, 1.0);
    }
    if (m->Get(AI_MATKEY_OPACITY, f) == AI_SUCCESS && f < 0.99f) {
      out.transmission = std::clamp(1.0 - f, 0.0, 1.0);
      textured = true;
    }
    if (m->Get(AI_MATKEY_COLOR_EMISSIVE, c) == AI_SUCCESS && (c.r + c.g + c.b) > 0.0f) {
      out.emission = {c.r, c.g, c.b};
      out.light = LightRole::kAlways;
      textured = true;
    }
    aiString path;
    if (m->GetTexture(aiTextureType_BASE_COLOR, 0, &path) == AI_SUCCESS ||
        m->GetTexture(aiTextureType_DIFFUSE, 0, &path) == AI_SUCCESS) {
      out.image = texture(path.C_Str());
      if (out.image) {
        out.base_color = {1.0, 1.0, 1.0};
        if (m->Get(AI_MATKEY_BASE_COLOR, c) == AI_SUCCESS) {
          out.base_color = {c.r, c.g, c.b};
        }
        textured = true;
      }
    }
    return out;
  }
};

struct Walker {
  const aiScene* scene;
  const Placer* placer;
  bool y_up;
  const ModelPlacement* placement;
  std::string file;
  std::vector<StaticMesh> out;
  MaterialReader* materials = nullptr;

  void node(const aiNode* n, const aiMatrix4x4& parent) {
    const aiMatrix4x4 m = parent * n->mTransformation;
    for (unsigned i = 0; i < n->mNumMeshes; ++i) {
      mesh(scene->mMeshes[n->mMeshes[i]], m, n->mName.C_Str());
    }
    for (unsigned c = 0; c < n->mNumChildren; ++c) {
      node(n->mChildren[c], m);
    }
  }

  void mesh(const aiMesh* mesh, const aiMatrix4x4& m, const std::string& node_name) {
    StaticMesh s;
    s.name = file + ":" + (node_name.empty() ? std::string(mesh->mName.C_Str()) : node_name);
    s.classes = {placement->semantic};
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
      const aiVector3D p = m * mesh->mVertices[v];
      // y-up (x right, y up, z towards the viewer) to z-up (x east, y north, z up).
      const Vec3 local = y_up ? Vec3{p.x, -p.z, p.y} : Vec3{p.x, p.y, p.z};
      s.vertices.push_back(placer->place(local));
    }
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const aiFace& face = mesh->mFaces[f];
      if (face.mNumIndices == 3) {
        s.triangles.push_back({face.mIndices[0], face.mIndices[1], face.mIndices[2]});
      }
    }
    if (scene->mNumMaterials > mesh->mMaterialIndex && materials != nullptr) {
      bool textured = false;
      Material m = materials->read(mesh->mMaterialIndex, textured);
      if (textured) {
        s.materials = {m};
        if (mesh->HasTextureCoords(0)) {
          for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
            s.uvs.push_back({mesh->mTextureCoords[0][v].x, mesh->mTextureCoords[0][v].y});
          }
        }
      }
    }
    if (scene->mNumMaterials > mesh->mMaterialIndex) {
      aiColor4D diffuse;
      if (scene->mMaterials[mesh->mMaterialIndex]->Get(AI_MATKEY_COLOR_DIFFUSE, diffuse) ==
          AI_SUCCESS) {
        auto byte = [](float x) {
          return static_cast<uint8_t>(std::lround(255.0 * std::clamp(x, 0.0f, 1.0f)));
        };
        s.color = Rgb8{byte(diffuse.r), byte(diffuse.g), byte(diffuse.b)};
      }
    }
    if (!s.triangles.empty()) {
      out.push_back(std::move(s));
    }
  }
};

}  // namespace

std::vector<StaticMesh> load_model(const std::filesystem::path& path,
                                   const ModelPlacement& placement) {
  check_input_file(path);  // a regular file of bounded size: assimp would block on a FIFO
  if (!(placement.scale > 0.0) || !std::isfinite(placement.scale)) {
    fail(path, "model scale must be a positive number");
  }
  Assimp::Importer importer;
  const aiScene* scene =
      importer.ReadFile(path.string(), aiProcess_Triangulate | aiProcess_JoinIdenticalVertices |
                                           aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (scene == nullptr || scene->mRootNode == nullptr ||
      (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0) {
    fail(path, std::string("cannot read the model: ") + importer.GetErrorString());
  }
  const Placer placer(path, placement);
  MaterialReader materials{scene, path, placement.diagnostics, {}};
  Walker walker{
      scene, &placer,   y_up_for(path, placement.up_axis), &placement, path.filename().string(),
      {},    &materials};
  walker.node(scene->mRootNode, aiMatrix4x4());
  if (walker.out.empty()) {
    fail(path, "the model has no triangles");
  }
  return std::move(walker.out);
}

void write_model(const std::vector<StaticMesh>& meshes, const std::filesystem::path& path,
                 const std::string& format, bool y_up) {
  aiScene scene;
  scene.mRootNode = new aiNode("root");
  scene.mNumMeshes = static_cast<unsigned>(meshes.size());
  scene.mMeshes = new aiMesh*[meshes.size()];
  scene.mNumMaterials = static_cast<unsigned>(meshes.size());
  scene.mMaterials = new aiMaterial*[meshes.size()];
  scene.mRootNode->mNumChildren = static_cast<unsigned>(meshes.size());
  scene.mRootNode->mChildren = new aiNode*[meshes.size()];
  for (size_t i = 0; i < meshes.size(); ++i) {
    const StaticMesh& s = meshes[i];
    auto* mesh = new aiMesh();
    mesh->mName = s.name;
    mesh->mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
    mesh->mMaterialIndex = static_cast<unsigned>(i);
    mesh->mNumVertices = static_cast<unsigned>(s.vertices.size());
    mesh->mVertices = new aiVector3D[s.vertices.size()];
    for (size_t v = 0; v < s.vertices.size(); ++v) {
      const Vec3 p = s.vertices[v];
      mesh->mVertices[v] = y_up ? aiVector3D(static_cast<float>(p.x), static_cast<float>(p.z),
                                             static_cast<float>(-p.y))
                                : aiVector3D(static_cast<float>(p.x), static_cast<float>(p.y),
                                             static_cast<float>(p.z));
    }
    mesh->mNumFaces = static_cast<unsigned>(s.triangles.size());
    mesh->mFaces = new aiFace[s.triangles.size()];
    for (size_t f = 0; f < s.triangles.size(); ++f) {
      aiFace& face = mesh->mFaces[f];
      face.mNumIndices = 3;
      face.mIndices = new unsigned[3]{s.triangles[f][0], s.triangles[f][1], s.triangles[f][2]};
    }
    scene.mMeshes[i] = mesh;
    auto* material = new aiMaterial();
    const Rgb8 c = s.color.value_or(Rgb8{180, 170, 150});
    const aiColor4D diffuse(c.r / 255.0f, c.g / 255.0f, c.b / 255.0f, 1.0f);
    material->AddProperty(&diffuse, 1, AI_MATKEY_COLOR_DIFFUSE);
    const aiString name("material_" + std::to_string(i));
    material->AddProperty(&name, AI_MATKEY_NAME);
    scene.mMaterials[i] = material;
    auto* node = new aiNode(s.name);
    node->mParent = scene.mRootNode;
    node->mNumMeshes = 1;
    node->mMeshes = new unsigned[1]{static_cast<unsigned>(i)};
    scene.mRootNode->mChildren[i] = node;
  }
  // Export into a private folder beside the target, then rename each file into place, so that
  // multi-file formats (glTF's .bin, OBJ's .mtl) keep the names the main file refers to and no
  // half-written file ever appears under a final name.
  namespace fs = std::filesystem;
  const fs::path folder = path.parent_path().empty() ? fs::path(".") : path.parent_path();
  const fs::path staging = folder / ("." + path.filename().string() + ".export");
  std::error_code ignored;
  fs::remove_all(staging, ignored);
  fs::create_directories(staging, ignored);
  Assimp::Exporter exporter;
  const aiReturn result = exporter.Export(&scene, format, (staging / path.filename()).string());
  if (result != aiReturn_SUCCESS) {
    fs::remove_all(staging, ignored);
    fail(path, "cannot export the model as " + format + ": " + exporter.GetErrorString());
  }
  std::vector<fs::path> produced;
  for (const auto& entry : fs::directory_iterator(staging)) {
    produced.push_back(entry.path());
  }
  std::sort(produced.begin(), produced.end());
  for (const auto& file : produced) {
    fs::rename(file, folder / file.filename());
  }
  fs::remove_all(staging, ignored);
}

}  // namespace corsa::sensors
