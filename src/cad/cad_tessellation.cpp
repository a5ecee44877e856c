#include "cad/cad_tessellation.h"

#include <cmath>
#include <filesystem>
#include <string>
#include <system_error>

#include "common/cad_file.h"
#include "common/input_error.h"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESModel.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <Message_Printer.hxx>
#include <Poly_Triangulation.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Solid.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <UnitsMethods.hxx>

#include <algorithm>
#include <array>
#include <utility>
#include <vector>

#include "geometry/position_weld.h"

namespace peensim {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
    throw InputError(SourceLocation{path, 0, 0}, "mesh", problem);
}

// Points closer than this share a vertex, as a share of the model's bounding-box diagonal: far
// above the round-off of placing a node (1e-15 relative), far below the shortest triangle edge
// BRepMesh makes (a tenth of the chordal tolerance; 1e-9 of a 100 mm part is 0.1 nm).
constexpr double kWeldTolerance = 1e-9;

// OpenCASCADE reports through one process-wide messenger that prints to stdout. While a file is
// read, its printers are swapped for one that keeps the warnings and failures, which an error
// then quotes; peensim's own output stays clean. Not for two readers on two threads at once
// (components are loaded one after the other).
class KeptMessages : public Message_Printer {
public:
    std::string last_failures(std::size_t count) const {
        std::string out;
        for (std::size_t k = messages_.size() > count ? messages_.size() - count : 0; k < messages_.size(); ++k)
            out += (out.empty() ? "" : "; ") + messages_[k];
        return out;
    }

protected:
    void send(const TCollection_AsciiString& text, const Message_Gravity gravity) const override {
        if (gravity < Message_Alarm) return;
        std::string line(text.ToCString());
        // "**** ERR StepFile : ... ****": keep the words.
        line.erase(0, line.find_first_not_of("* "));
        line.erase(line.find_last_not_of("* \n") + 1);
        if (!line.empty()) messages_.push_back(line);
    }

private:
    mutable std::vector<std::string> messages_;
};

class MessagesKept {
public:
    MessagesKept() : messenger_(Message::DefaultMessenger()), saved_(messenger_->Printers()), kept_(new KeptMessages) {
        messenger_->ChangePrinters().Clear();
        messenger_->AddPrinter(kept_);
    }
    ~MessagesKept() { messenger_->ChangePrinters() = saved_; }
    MessagesKept(const MessagesKept&) = delete;
    MessagesKept& operator=(const MessagesKept&) = delete;

    // " (OpenCASCADE: ...)" with the last messages, or "".
    std::string quoted() const {
        const std::string text = kept_->last_failures(2);
        return text.empty() ? std::string() : " (OpenCASCADE: " + text + ")";
    }

private:
    Handle(Message_Messenger) messenger_;
    Message_SequenceOfPrinters saved_;
    Handle(KeptMessages) kept_;
};

struct ReadShape {
    TopoDS_Shape shape;
    double unit_m = 1e-3;       // m per length unit of `shape` (OpenCASCADE's session unit)
    std::string declared_unit;  // the file's own length unit as it names it, "" if it names none
};

// The file's shapes, converted by OpenCASCADE from the file's unit into its session unit.
template <typename Reader>
ReadShape read_with(Reader& reader, const std::string& path, const char* format, const MessagesKept& messages) {
    if (reader.ReadFile(path.c_str()) != IFSelect_RetDone) fail(path, std::string("cannot read ") + format + " file" + messages.quoted());
    reader.TransferRoots();
    if (reader.NbShapes() == 0) fail(path, std::string(format) + " file holds no shape" + messages.quoted());
    return {reader.OneShape(), 1e-3, {}};
}

ReadShape read_shape(const std::string& path, const MessagesKept& messages) {
    if (is_iges_file(path)) {
        IGESControl_Reader reader;
        ReadShape read = read_with(reader, path, "IGES", messages);
        read.unit_m = UnitsMethods::GetCasCadeLengthUnit() * 1e-3;  // mm per session unit
        if (const Handle(IGESData_IGESModel) model = reader.IGESModel(); !model.IsNull()) {
            const Handle(TCollection_HAsciiString) name = model->GlobalSection().UnitName();
            if (!name.IsNull()) read.declared_unit = name->ToCString();
        }
        return read;
    }
    STEPControl_Reader reader;
    ReadShape read = read_with(reader, path, "STEP", messages);
    read.unit_m = reader.SystemLengthUnit() * 1e-3;  // mm per session unit
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    reader.FileUnits(lengths, angles, solid_angles);
    // One name per unit the file declares; most declare one (an assembly of parts in other units
    // lists each, and OpenCASCADE converts each part from its own).
    std::vector<std::string> names;
    for (int i = 1; i <= lengths.Length(); ++i) {
        const std::string name = lengths.Value(i).ToCString();
        if (std::find(names.begin(), names.end(), name) != names.end()) continue;
        read.declared_unit += (names.empty() ? "" : ", ") + name;
        names.push_back(name);
    }
    return read;
}

struct Group {
    std::string name;
    TopoDS_Shape shape;
};

// The solids of the file, then its faces outside any solid sewn together (an IGES file of trimmed
// surfaces, a STEP surface model): a closed sewn shell becomes a solid (oriented outward by
// ShapeFix), the rest is "surface". Sewing joins edges closer than `sewing_tolerance` (file units).
std::vector<Group> groups_of(const TopoDS_Shape& shape, double sewing_tolerance) {
    std::vector<Group> groups;
    for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next())
        groups.push_back({"solid" + std::to_string(groups.size() + 1), e.Current()});
    BRepBuilderAPI_Sewing sewing(sewing_tolerance);
    int loose = 0;
    for (TopExp_Explorer e(shape, TopAbs_FACE, TopAbs_SOLID); e.More(); e.Next(), ++loose) sewing.Add(e.Current());
    if (loose == 0) return groups;
    sewing.Perform();
    BRep_Builder builder;
    TopoDS_Compound surface;
    builder.MakeCompound(surface);
    bool any_surface = false;
    const TopoDS_Shape sewn = sewing.SewedShape();
    for (TopExp_Explorer e(sewn, TopAbs_SHELL); e.More(); e.Next()) {
        const TopoDS_Shell shell = TopoDS::Shell(e.Current());
        if (BRep_Tool::IsClosed(shell)) {
            groups.push_back({"solid" + std::to_string(groups.size() + 1), ShapeFix_Solid().SolidFromShell(shell)});
        } else {
            builder.Add(surface, shell);
            any_surface = true;
        }
    }
    for (TopExp_Explorer e(sewn, TopAbs_FACE, TopAbs_SHELL); e.More(); e.Next()) {
        builder.Add(surface, e.Current());
        any_surface = true;
    }
    if (any_surface) groups.push_back({"surface", surface});
    return groups;
}

double diagonal_of(const TopoDS_Shape& shape) {
    Bnd_Box box;
    BRepBndLib::Add(shape, box);
    if (box.IsVoid()) return 0.0;
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    return std::hypot(x1 - x0, y1 - y0, z1 - z0);
}

struct Corners {
    std::array<int, 3> vertex;
    int facet;
    int group;
};

TriangleMesh tessellate(const std::string& path, const ReadShape& read, const Tessellation& tessellation) {
    const double chordal = tessellation.chordal_m / read.unit_m;  // file (session) units
    const std::vector<Group> groups = groups_of(read.shape, chordal);
    if (groups.empty()) fail(path, "file holds no solid and no face (only curves or points?): nothing to tessellate");

    BRep_Builder builder;
    TopoDS_Compound all;
    builder.MakeCompound(all);
    for (const Group& g : groups) builder.Add(all, g.shape);
    IMeshTools_Parameters parameters;
    parameters.Deflection = chordal;
    parameters.DeflectionInterior = chordal;  // the default, stated
    parameters.Angle = tessellation.angular_rad;
    parameters.AngleInterior = tessellation.angular_rad;  // (BRepMesh's default: twice the edges')
    parameters.Relative = false;                          // absolute tolerances, whatever the face's size
    parameters.InParallel = false;                        // one part; a result that depends on nothing but the file
    parameters.ControlSurfaceDeflection = true;           // the chordal tolerance checked inside faces, not only on edges
    BRepMesh_IncrementalMesh mesher(all, parameters);

    const double diagonal = diagonal_of(all);
    PositionWeld weld(diagonal > 0.0 ? kWeldTolerance * diagonal : 1e-12);
    std::vector<Corners> corners;
    TriangleMesh out;
    int facet = 0;
    std::size_t untessellated = 0;
    std::vector<int> node_vertex;
    for (std::size_t g = 0; g < groups.size(); ++g) {
        out.group_names.push_back(groups[g].name);
        for (TopExp_Explorer e(groups[g].shape, TopAbs_FACE); e.More(); e.Next(), ++facet) {
            const TopoDS_Face face = TopoDS::Face(e.Current());
            TopLoc_Location location;
            const Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
            if (triangulation.IsNull() || triangulation->NbTriangles() == 0) {
                ++untessellated;
                continue;
            }
            const gp_Trsf placement = location.Transformation();
            node_vertex.assign(static_cast<std::size_t>(triangulation->NbNodes()) + 1, -1);
            for (int n = 1; n <= triangulation->NbNodes(); ++n) {
                const gp_Pnt p = triangulation->Node(n).Transformed(placement);
                const Vec3 position(p.X(), p.Y(), p.Z());
                if (!position.allFinite()) fail(path, "face " + std::to_string(facet) + " has a non-finite coordinate");
                node_vertex[static_cast<std::size_t>(n)] = weld.vertex(position);
            }
            // Triangles run counter-clockwise about the surface's own normal; a reversed face's
            // outside is the other side.
            const bool reversed = face.Orientation() == TopAbs_REVERSED;
            for (int t = 1; t <= triangulation->NbTriangles(); ++t) {
                int a = 0, b = 0, c = 0;
                triangulation->Triangle(t).Get(a, b, c);
                if (reversed) std::swap(b, c);
                corners.push_back({{node_vertex[static_cast<std::size_t>(a)], node_vertex[static_cast<std::size_t>(b)],
                                    node_vertex[static_cast<std::size_t>(c)]},
                                   facet,
                                   static_cast<int>(g)});
            }
        }
    }

    // Triangles of zero area after welding (a pole of a sphere or cone, a sliver) are dropped; so
    // are the vertices only they used. A face is lost when none of its triangles is kept.
    const std::vector<Vec3>& welded = weld.vertices();
    std::vector<int> new_index(welded.size(), -1);
    std::vector<char> face_kept(static_cast<std::size_t>(facet), 0), face_had(static_cast<std::size_t>(facet), 0);
    for (const Corners& t : corners) {
        face_had[static_cast<std::size_t>(t.facet)] = 1;
        const auto& v = t.vertex;
        if (v[0] == v[1] || v[1] == v[2] || v[2] == v[0]) continue;
        const Vec3& p = welded[static_cast<std::size_t>(v[0])];
        if ((welded[static_cast<std::size_t>(v[1])] - p).cross(welded[static_cast<std::size_t>(v[2])] - p).squaredNorm() == 0.0) continue;
        std::array<int, 3> renumbered{};
        for (std::size_t k = 0; k < 3; ++k) {
            int& index = new_index[static_cast<std::size_t>(v[k])];
            if (index < 0) {
                index = static_cast<int>(out.vertices.size());
                out.vertices.push_back(welded[static_cast<std::size_t>(v[k])] * read.unit_m);
            }
            renumbered[k] = index;
        }
        out.triangles.push_back(renumbered);
        out.source_facet.push_back(t.facet);
        out.group_of_triangle.push_back(t.group);
        face_kept[static_cast<std::size_t>(t.facet)] = 1;
    }
    out.dropped_degenerate_facets = untessellated;
    for (std::size_t f = 0; f < face_had.size(); ++f) out.dropped_degenerate_facets += face_had[f] && !face_kept[f];
    if (out.triangles.empty())
        fail(path, "no triangle of non-zero area from its " + std::to_string(facet) + " faces (" + std::to_string(untessellated) +
                       " could not be tessellated)");
    return out;
}

}  // namespace

TriangleMesh tessellate_cad_file(const std::string& path, const Tessellation& tessellation) {
    if (!(tessellation.chordal_m > 0.0) || !std::isfinite(tessellation.chordal_m))
        fail(path, "the chordal tolerance must be a positive length");
    if (!(tessellation.angular_rad > 0.0) || !std::isfinite(tessellation.angular_rad))
        fail(path, "the angular tolerance must be a positive angle");
    std::error_code error;
    if (std::filesystem::file_size(path, error) == 0 && !error) fail(path, "the file is empty");
    MessagesKept messages;
    try {
        const ReadShape read = read_shape(path, messages);
        if (!(read.unit_m > 0.0) || !std::isfinite(read.unit_m)) fail(path, "OpenCASCADE's session length unit is not a length");
        TriangleMesh mesh = tessellate(path, read, tessellation);
        mesh.declared_unit = read.declared_unit;
        return mesh;
    } catch (const Standard_Failure& e) {
        fail(path, std::string("OpenCASCADE failed on the file: ") + e.GetMessageString() + messages.quoted());
    }
}

}  // namespace peensim
