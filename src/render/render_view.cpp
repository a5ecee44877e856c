#include "render/render_view.h"

#include "geometry/mesh_checks.h"

namespace peensim {

std::vector<Vec3> world_vertices(const Component& c) {
    const Pose rest = c.kinematics.pose(SimTime{});
    std::vector<Vec3> points;
    points.reserve(c.mesh->vertices.size());
    for (const Vec3& v : c.mesh->vertices) points.push_back(rest.to_world(v));
    return points;
}

render::Rgba role_colour(ComponentRole role) {
    switch (role) {
        case ComponentRole::sonotrode: return {0.45f, 0.55f, 0.70f, 1.0f};
        case ComponentRole::chamber: return {0.62f, 0.64f, 0.68f, 1.0f};
        case ComponentRole::part: return {0.86f, 0.62f, 0.30f, 1.0f};
        case ComponentRole::fixture: return {0.55f, 0.48f, 0.40f, 1.0f};
        case ComponentRole::almen: return {0.40f, 0.60f, 0.80f, 1.0f};
    }
    return {0.7f, 0.7f, 0.7f, 1.0f};
}

ModelView add_model(render::Renderer& renderer, const Model& model) {
    ModelView view;
    bool any_chamber = false;
    for (const Component& c : model.components) {
        render::MeshStyle style;
        style.colour = role_colour(c.role);
        if (c.role == ComponentRole::chamber) {
            // Seen from outside, drop the walls whose faces look at the camera: the inner faces
            // of the far walls stay. Which side that is depends on the mesh's winding: a chamber
            // whose normals face the cavity has a negative enclosed volume.
            style.cull = enclosed_volume(*c.mesh) < 0.0 ? render::Cull::back : render::Cull::front;
            view.chamber_lo = any_chamber ? view.chamber_lo.cwiseMin(c.world_lo) : c.world_lo;
            view.chamber_hi = any_chamber ? view.chamber_hi.cwiseMax(c.world_hi) : c.world_hi;
            any_chamber = true;
            const std::vector<Vec3> points = world_vertices(c);
            view.chamber_points.insert(view.chamber_points.end(), points.begin(), points.end());
        }
        view.meshes.push_back(renderer.add_mesh(*c.mesh, style));
    }
    if (!any_chamber) {
        view.chamber_lo = model.world_lo;
        view.chamber_hi = model.world_hi;
        for (const Vec3& v : {model.world_lo, model.world_hi}) view.chamber_points.push_back(v);
    }
    pose_model(renderer, view, model, SimTime{});
    return view;
}

void pose_model(render::Renderer& renderer, const ModelView& view, const Model& model, const SimTime& t, double offset_s) {
    for (std::size_t i = 0; i < model.components.size(); ++i) {
        const Pose p = model.components[i].kinematics.pose(t, offset_s);
        renderer.set_pose(view.meshes[i], render::make_pose(p.rotation, p.translation));
    }
}

render::Camera scene_camera(const RenderDesc& desc, const ModelView& view, double aspect) {
    const double fov_deg = desc.fov_rad * 180.0 / M_PI;
    if (!desc.camera_position_m)
        return render::Camera::framing_points(view.chamber_points, aspect, render::Camera::default_view_direction(), fov_deg);
    render::Camera camera;
    camera.position_m = *desc.camera_position_m;
    camera.look_at_m = desc.camera_look_at_m.value_or(0.5 * (view.chamber_lo + view.chamber_hi));
    camera.up = desc.camera_up;
    camera.vertical_fov_deg = fov_deg;
    camera.fit_depth_range(view.chamber_lo, view.chamber_hi);
    return camera;
}

}  // namespace peensim
