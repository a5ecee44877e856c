#include "output/vtk_collection.h"

#include <charconv>

#include "output/xml_text.h"

namespace peensim {

void write_pvd(const std::string& path, std::span<const TimeStepFile> steps, Durability durability) {
    std::string xml =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        "  <Collection>\n";
    char time[32];
    for (const TimeStepFile& s : steps) {
        const auto end = std::to_chars(time, time + sizeof time, s.time_s).ptr;  // shortest round-trip form
        xml += "    <DataSet timestep=\"" + std::string(time, end) + "\" part=\"0\" file=\"" + xml_text(s.file) + "\"/>\n";
    }
    xml += "  </Collection>\n</VTKFile>\n";
    write_file_atomically(path, xml, durability);
}

void write_vtm(const std::string& path, std::span<const NamedBlock> blocks) {
    std::string xml =
        "<?xml version=\"1.0\"?>\n"
        "<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
        "  <vtkMultiBlockDataSet>\n";
    for (std::size_t i = 0; i < blocks.size(); ++i) {
        xml += "    <DataSet index=\"" + std::to_string(i) + "\" name=\"" + xml_text(blocks[i].name) + "\" file=\"" +
               xml_text(blocks[i].file) + "\"/>\n";
    }
    xml += "  </vtkMultiBlockDataSet>\n</VTKFile>\n";
    write_file_atomically(path, xml);
}

}  // namespace peensim
