#include "fem/inp_writer.h"

#include <cstdio>
#include <ostream>
#include <string>

namespace peensim {

namespace {

constexpr int kIdsPerLine = 8;                       // ids per data line (the format allows 16)
constexpr double kRelaxationInitialIncrement = 0.1;  // -, of the relaxation step's unit (pseudo-)time

// CalculiX reads at most 20 characters a field: 12 significant digits ("-1.23456789012e-05", 18).
std::string inp_number(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    return buf;
}

// "*NSET, NSET=NAME" and its ids, kIdsPerLine to a line.
template <class Ids>
void write_set(std::ostream& out, const char* keyword, const std::string& name, const Ids& ids) {
    out << "*" << keyword << ", " << keyword << "=" << name << "\n";
    int on_line = 0;
    for (int id : ids) {
        if (on_line > 0) out << ", ";
        out << id;
        if (++on_line == kIdsPerLine) {
            out << "\n";
            on_line = 0;
        }
    }
    if (on_line > 0) out << "\n";
}

std::vector<int> block_nodes(const std::vector<int>& nodes) {
    std::vector<int> ids;
    ids.reserve(nodes.size());
    for (int n : nodes) ids.push_back(block_node_id(n));
    return ids;
}

void write_material(std::ostream& out, const FemMaterial& m) {
    out << "*MATERIAL, NAME=" << m.name << "\n*ELASTIC\n" << inp_number(m.youngs_modulus_pa) << ", " << inp_number(m.poisson_ratio) << "\n";
    if (m.yield_stress_pa) {
        out << "*PLASTIC\n" << inp_number(*m.yield_stress_pa) << ", 0.\n";
        // Linear isotropic hardening: a second point at a plastic strain of 1.
        if (m.hardening_modulus_pa > 0.0) out << inp_number(*m.yield_stress_pa + m.hardening_modulus_pa) << ", 1.\n";
    }
    out << "*DENSITY\n" << inp_number(m.density_kg_per_m3) << "\n";
}

}  // namespace

void write_inp(std::ostream& out, const FemDeck& d) {
    for (const std::string& line : d.header) out << "**" << (line.empty() ? "" : " ") << line << "\n";
    out << "*HEADING\n" << d.heading << "\n";

    // Nodes and elements: the block, then each shot (the shot mesh moved to its start).
    const HexMesh& block = d.block.mesh;
    out << "** The target block (patch frame: surface z = 0, material z < 0)\n*NODE, NSET=NBLOCK\n";
    for (std::size_t i = 0; i < block.nodes.size(); ++i) {
        const Vec3& p = block.nodes[i];
        out << block_node_id(static_cast<int>(i)) << ", " << inp_number(p.x()) << ", " << inp_number(p.y()) << ", " << inp_number(p.z())
            << "\n";
    }
    out << "*ELEMENT, TYPE=" << fem_element_name(d.block_element) << ", ELSET=EBLOCK\n";
    for (std::size_t e = 0; e < block.elements.size(); ++e) {
        out << block_element_id(static_cast<int>(e));
        for (int n : block.elements[e]) out << ", " << block_node_id(n);
        out << "\n";
    }
    const HexMesh& ball = d.shot_mesh.mesh;
    for (std::size_t s = 0; s < d.shots.size(); ++s) {
        const int si = static_cast<int>(s);
        const FemShot& shot = d.shots[s];
        const std::string tag = std::to_string(s + 1);
        out << "** Shot " << tag << " (impact " << shot.impact + 1 << ", step " << shot.step + 1 << ")\n*NODE, NSET=NSHOT" << tag << "\n";
        for (std::size_t i = 0; i < ball.nodes.size(); ++i) {
            const Vec3 p = ball.nodes[i] + shot.start_centre_m;
            out << shot_node_id(d, si, static_cast<int>(i)) << ", " << inp_number(p.x()) << ", " << inp_number(p.y()) << ", "
                << inp_number(p.z()) << "\n";
        }
        out << "*ELEMENT, TYPE=C3D8, ELSET=ESHOT" << tag << "\n";
        for (std::size_t e = 0; e < ball.elements.size(); ++e) {
            out << shot_element_id(d, si, static_cast<int>(e));
            for (int n : ball.elements[e]) out << ", " << shot_node_id(d, si, n);
            out << "\n";
        }
    }

    // Sets and surfaces.
    write_set(out, "NSET", "NTOP", block_nodes(d.block.top));
    write_set(out, "NSET", "NBOTTOM", block_nodes(d.block.bottom));
    write_set(out, "NSET", "NXMIN", block_nodes(d.block.x_min));
    write_set(out, "NSET", "NXMAX", block_nodes(d.block.x_max));
    write_set(out, "NSET", "NYMIN", block_nodes(d.block.y_min));
    write_set(out, "NSET", "NYMAX", block_nodes(d.block.y_max));
    write_set(out, "NSET", "NPROFILE", block_nodes(d.block.profile));
    std::vector<int> ids;
    for (int e : d.block.top_elements) ids.push_back(block_element_id(e));
    write_set(out, "ELSET", "ETOP", ids);
    ids.clear();
    for (int e : d.block.axis_elements) ids.push_back(block_element_id(e));
    write_set(out, "ELSET", "EAXIS", ids);
    ids.clear();
    for (std::size_t s = 0; s < d.shots.size(); ++s) ids.push_back(shot_node_id(d, static_cast<int>(s), d.shot_mesh.centre_node));
    write_set(out, "NSET", "NSHOTCENTRES", ids);
    if (!d.shots.empty()) {
        ids.clear();
        for (std::size_t s = 0; s < d.shots.size(); ++s)
            for (std::size_t e = 0; e < ball.elements.size(); ++e)
                ids.push_back(shot_element_id(d, static_cast<int>(s), static_cast<int>(e)));
        write_set(out, "ELSET", "ESHOTS", ids);
        for (int face = 1; face <= 6; ++face) {
            ids.clear();
            for (std::size_t s = 0; s < d.shots.size(); ++s)
                for (const HexFace& f : d.shot_mesh.surface)
                    if (f.face == face) ids.push_back(shot_element_id(d, static_cast<int>(s), f.element));
            if (!ids.empty()) write_set(out, "ELSET", "ESHOTF" + std::to_string(face), ids);
        }
    }
    if (d.quarter) {
        ids.clear();
        for (std::size_t s = 0; s < d.shots.size(); ++s)
            for (int n : d.shot_mesh.x0) ids.push_back(shot_node_id(d, static_cast<int>(s), n));
        write_set(out, "NSET", "NSHOTX0", ids);
        ids.clear();
        for (std::size_t s = 0; s < d.shots.size(); ++s)
            for (int n : d.shot_mesh.y0) ids.push_back(shot_node_id(d, static_cast<int>(s), n));
        write_set(out, "NSET", "NSHOTY0", ids);
    }
    out << "*SURFACE, NAME=STOP, TYPE=ELEMENT\nETOP, S2\n";
    out << "*SURFACE, NAME=SSHOTS, TYPE=ELEMENT\n";
    for (int face = 1; face <= 6; ++face) {
        bool any = false;
        for (const HexFace& f : d.shot_mesh.surface) any = any || f.face == face;
        if (any && !d.shots.empty()) out << "ESHOTF" << face << ", S" << face << "\n";
    }

    // Materials and sections.
    write_material(out, d.target);
    write_material(out, d.shot);
    out << "*SOLID SECTION, ELSET=EBLOCK, MATERIAL=" << d.target.name << "\n";
    if (!d.shots.empty()) out << "*SOLID SECTION, ELSET=ESHOTS, MATERIAL=" << d.shot.name << "\n";

    // Contact: penalty, frictionless; slave the block's top, master the shots' surfaces.
    out << "*SURFACE INTERACTION, NAME=SHOTCONTACT\n*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
        << inp_number(d.contact_stiffness_pa_per_m) << "\n";
    out << "*CONTACT PAIR, INTERACTION=SHOTCONTACT, TYPE=NODE TO SURFACE\nSTOP, SSHOTS\n";

    // Boundary conditions: bottom fixed, sides on rollers (normal displacement 0), symmetry planes.
    out << "*BOUNDARY\nNBOTTOM, 1, 3\nNXMAX, 1, 1\nNYMAX, 2, 2\nNXMIN, 1, 1\nNYMIN, 2, 2\n";
    if (d.quarter) out << "NSHOTX0, 1, 1\nNSHOTY0, 2, 2\n";

    // Every shot flies from t = 0 (placed so that it lands at the start of its step).
    if (!d.shots.empty()) {
        out << "*INITIAL CONDITIONS, TYPE=VELOCITY\n";
        for (std::size_t s = 0; s < d.shots.size(); ++s)
            for (int k = 0; k < 3; ++k)
                out << "NSHOT" << s + 1 << ", " << k + 1 << ", " << inp_number(d.shots[s].velocity_m_per_s[k]) << "\n";
    }

    for (std::size_t k = 0; k < d.steps.size(); ++k) {
        const FemStep& st = d.steps[k];
        out << "** Step " << k + 1 << ": shots";
        for (int s : st.shots) out << " " << s + 1;
        out << "\n*STEP, NLGEOM, INC=10000000\n";
        if (d.explicit_dynamics)  // ccx takes the stable (Courant) increment itself
            out << "*DYNAMIC, EXPLICIT\n" << inp_number(st.initial_increment_s) << ", " << inp_number(st.duration_s) << "\n";
        else
            out << "*DYNAMIC, ALPHA=" << inp_number(d.alpha) << "\n"
                << inp_number(st.initial_increment_s) << ", " << inp_number(st.duration_s) << ", "
                << inp_number(st.initial_increment_s * 1e-4) << ", " << inp_number(st.max_increment_s) << "\n";
        out << "*NODE PRINT, NSET=NPROFILE, FREQUENCY=1000000\nU\n";
        out << "*NODE PRINT, NSET=NSHOTCENTRES, FREQUENCY=1000000\nV\n";
        out << "*NODE FILE, FREQUENCY=1000000\nU\n*EL FILE, FREQUENCY=1000000\nS, PEEQ\n*END STEP\n";
    }

    // Relaxation: the stresses at the end of a dynamic step still carry the stress waves and the
    // part's inertia (a single impact showed -2 GPa hydrostatic at 220 um). A static step with the
    // contact removed and every shot held where it is (they have rebounded) lets the block come to
    // equilibrium: what it prints and writes then is the residual state.
    if (d.steps.empty()) return;
    out << "** Relaxation: static equilibrium without the shot, the residual state\n*STEP, NLGEOM, INC=1000\n*STATIC\n"
        << inp_number(kRelaxationInitialIncrement)
        << ", 1., 1e-05, 1.\n*MODEL CHANGE, TYPE=CONTACT PAIR, REMOVE\nSTOP, SSHOTS\n*BOUNDARY, FIXED\n";
    for (std::size_t s = 0; s < d.shots.size(); ++s) out << "NSHOT" << s + 1 << ", 1, 3\n";
    out << "*NODE PRINT, NSET=NPROFILE\nU\n*EL PRINT, ELSET=EAXIS\nS, PEEQ\n";
    out << "*NODE FILE\nU\n*EL FILE\nS, PEEQ\n*END STEP\n";
}

}  // namespace peensim
