// Writes the rod of scenes/rod.yaml as a STEP solid (OpenCASCADE; mm): radius 5 mm, 30 mm along y
// centred on y = 0, its axis 20 mm above the sonotrode's top face (assets/regenerate.sh's rod.stl, exact).
// For tests/validation/step_tessellation.py, which runs the rod scene on it at several tessellations.
//
//     build/peensim_write_step_rod OUT.step
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Controller.hxx>
#include <STEPControl_Writer.hxx>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2 || argv[1][0] == '-') {  // `--help` is a question, not a file to write
        std::fprintf(stderr, "usage: peensim_write_step_rod OUT.step\n");
        return 2;
    }
    Message::DefaultMessenger()->ChangePrinters().Clear();  // OpenCASCADE's progress lines on stdout
    const double radius_mm = 5.0, length_mm = 30.0, axis_z_mm = 20.0;
    const TopoDS_Shape rod =
        BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, -length_mm / 2, axis_z_mm), gp_Dir(0, 1, 0)), radius_mm, length_mm).Shape();
    STEPControl_Controller::Init();
    Interface_Static::SetCVal("write.step.unit", "MM");  // (before the writer: it converts with the unit of its making)
    STEPControl_Writer writer;
    if (writer.Transfer(rod, STEPControl_AsIs) != IFSelect_RetDone || writer.Write(argv[1]) != IFSelect_RetDone) {
        std::fprintf(stderr, "peensim_write_step_rod: cannot write %s\n", argv[1]);
        return 1;
    }
    return 0;
}
