#include "geometry/mesh_loader.h"

#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <vector>

#include "common/cad_file.h"
#include "common/input_error.h"
#include "geometry/mesh_builder.h"
#include "geometry/mesh_file_precheck.h"

namespace peensim {

namespace {

[[noreturn]] void fail_load(const std::string& path, const std::string& problem) {
    throw InputError(SourceLocation{path, 0, 0}, "mesh", problem);
}

struct MeshPlacement {
    aiMatrix4x4 transform;  // file units, node-to-scene
    std::string node_name;
    bool found = false;
};

// Where each assimp mesh sits: the first node (depth first) that references it.
void collect_placements(const aiNode* node, const aiMatrix4x4& parent, std::vector<MeshPlacement>& placements) {
    const aiMatrix4x4 transform = parent * node->mTransformation;
    for (unsigned i = 0; i < node->mNumMeshes; ++i) {
        MeshPlacement& placement = placements.at(node->mMeshes[i]);
        if (!placement.found) placement = {transform, node->mName.C_Str(), true};
    }
    for (unsigned c = 0; c < node->mNumChildren; ++c) collect_placements(node->mChildren[c], transform, placements);
}

// assimp names the nodes it invents "<STL_BINARY>", "<MD5_Root>", ...: not names from the file.
bool is_assimp_placeholder(const std::string& name) { return name.size() >= 2 && name.front() == '<' && name.back() == '>'; }

std::string group_name_of(const aiMesh& mesh, const MeshPlacement& placement) {
    if (mesh.mName.length > 0) return mesh.mName.C_Str();
    return is_assimp_placeholder(placement.node_name) ? std::string() : placement.node_name;
}

bool is_degenerate(const TriangleMesh& mesh, int a, int b, int c) {
    if (a == b || b == c || c == a) return true;
    const Vec3& p = mesh.vertices[static_cast<std::size_t>(a)];
    const Vec3 n = (mesh.vertices[static_cast<std::size_t>(b)] - p).cross(mesh.vertices[static_cast<std::size_t>(c)] - p);
    return n.squaredNorm() == 0.0;
}

// Scales to metres and drops the triangles of zero area, keeping the facet numbers of the
// others; vertices left unused by the dropped triangles are removed.
TriangleMesh without_degenerate_triangles(const TriangleMesh& welded, double unit_m) {
    TriangleMesh out;
    out.group_names = welded.group_names;
    std::vector<int> new_index(welded.vertices.size(), -1);
    // Facets with a triangle dropped, and with one kept: a facet is lost when it has none kept
    // (a quad with a repeated corner only loses a sliver of its fan, and is not counted).
    std::vector<int> dropped_from, kept_from;
    for (std::size_t t = 0; t < welded.triangles.size(); ++t) {
        const auto& tri = welded.triangles[t];
        if (is_degenerate(welded, tri[0], tri[1], tri[2])) {
            dropped_from.push_back(welded.source_facet[t]);
            continue;
        }
        kept_from.push_back(welded.source_facet[t]);
        std::array<int, 3> renumbered{};
        for (std::size_t k = 0; k < 3; ++k) {
            int& index = new_index[static_cast<std::size_t>(tri[k])];
            if (index < 0) {
                index = static_cast<int>(out.vertices.size());
                out.vertices.push_back(welded.vertices[static_cast<std::size_t>(tri[k])] * unit_m);
            }
            renumbered[k] = index;
        }
        out.triangles.push_back(renumbered);
        out.source_facet.push_back(welded.source_facet[t]);
        out.group_of_triangle.push_back(welded.group_of_triangle[t]);
    }
    std::sort(dropped_from.begin(), dropped_from.end());
    dropped_from.erase(std::unique(dropped_from.begin(), dropped_from.end()), dropped_from.end());
    std::sort(kept_from.begin(), kept_from.end());
    for (int f : dropped_from) out.dropped_degenerate_facets += !std::binary_search(kept_from.begin(), kept_from.end(), f);
    return out;
}

}  // namespace

TriangleMesh load_mesh(const std::string& path, double unit_m) { return load_mesh(path, MeshFileOptions{unit_m, Tessellation{}}); }

TriangleMesh load_mesh(const std::string& path, const MeshFileOptions& options) {
    const double unit_m = options.unit_m;
    if (!(unit_m > 0.0) || !std::isfinite(unit_m)) fail_load(path, "the mesh unit must be a positive length");
    std::error_code error;
    if (!std::filesystem::exists(path, error)) fail_load(path, "mesh file not found");
    if (!std::filesystem::is_regular_file(path, error)) fail_load(path, "not a regular file");
    if (is_cad_file(path)) return read_cad_mesh(path, options.tessellation);

    precheck_mesh_file(path);
    Assimp::Importer importer;
    // No post-processing: assimp's triangulation and vertex joining would lose the facet map
    // (and joining compares normals); both are done here instead.
    const aiScene* scene = importer.ReadFile(path, 0U);
    if (scene == nullptr) fail_load(path, std::string("cannot read mesh file: ") + importer.GetErrorString());
    if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) != 0U) fail_load(path, "mesh file is incomplete");

    std::vector<MeshPlacement> placements(scene->mNumMeshes);
    if (scene->mRootNode != nullptr) collect_placements(scene->mRootNode, aiMatrix4x4(), placements);

    MeshBuilder builder;
    std::size_t faces = 0;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) faces += scene->mMeshes[m]->mNumFaces;
    builder.reserve(faces);
    int facet = 0;
    std::vector<int> corners;
    for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
        const aiMesh& mesh = *scene->mMeshes[m];
        const MeshPlacement& placement = placements[m];
        const int group = builder.group(group_name_of(mesh, placement));
        for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
            const aiFace& face = mesh.mFaces[f];
            if (face.mNumIndices < 3) continue;  // a point or a line, not a facet
            corners.clear();
            for (unsigned k = 0; k < face.mNumIndices; ++k) {
                if (face.mIndices[k] >= mesh.mNumVertices)
                    fail_load(path, "facet " + std::to_string(facet) + " refers to a missing vertex");
                aiVector3D p = mesh.mVertices[face.mIndices[k]];
                if (placement.found && !placement.transform.IsIdentity()) p = placement.transform * p;
                const Vec3 position(p.x, p.y, p.z);
                if (!position.allFinite()) fail_load(path, "facet " + std::to_string(facet) + " has a non-finite coordinate");
                // Weld on the file's values; scaling identical values gives identical results.
                corners.push_back(builder.vertex(position));
            }
            for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
                builder.add_triangle(corners[0], corners[k], corners[k + 1], facet, group);
            }
            ++facet;
        }
    }

    TriangleMesh out = without_degenerate_triangles(builder.take(), unit_m);
    if (out.triangles.empty()) {
        fail_load(path, facet == 0
                            ? "mesh file contains no triangles"
                            : "mesh file contains no triangle of non-zero area (" + std::to_string(facet) + " facets, all degenerate)");
    }
    return out;
}

}  // namespace peensim
