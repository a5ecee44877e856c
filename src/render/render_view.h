// How peensim shows a model with the renderer: one mesh per component in its role's colour (the
// chamber cut away so the inside shows), poses at a given time, and the camera of the scene's
// `render` block or an automatic framing of the chamber. Shared by the frames recorded during a
// run and by `peensim render-impacts`.
#pragma once

#include <vector>

#include "model/model.h"
#include "render/renderer.h"
#include "scene/scene_description.h"

namespace peensim {

struct ModelView {
    std::vector<render::MeshId> meshes;  // per component, in model order
    Vec3 chamber_lo = Vec3::Zero();      // m, world box of the chamber(s) at t = 0
    Vec3 chamber_hi = Vec3::Zero();      // m
    std::vector<Vec3> chamber_points;    // m, world vertices of the chamber(s) at t = 0 (for framing)
};

// A component's vertices in the world at t = 0 (m): what automatic framings fit.
std::vector<Vec3> world_vertices(const Component& component);

// The colour a component of `role` is drawn in.
render::Rgba role_colour(ComponentRole role);

// Adds every component of the model to the renderer (chamber walls facing the camera culled).
ModelView add_model(render::Renderer& renderer, const Model& model);

// Moves every component to its pose at time t + offset_s.
void pose_model(render::Renderer& renderer, const ModelView& view, const Model& model, const SimTime& t, double offset_s = 0.0);

// The camera of `desc` for an image of `aspect` (width / height): its position and look-at when
// given, else a framing of the chamber's vertices from front-above.
render::Camera scene_camera(const RenderDesc& desc, const ModelView& view, double aspect);

}  // namespace peensim
