// The VTK XML settings every .vti / .vtp of forestwind shares, in one place: binary appended data (raw bytes,
// not base64), LZ4 compression, 64-bit headers (frames over 4 GiB uncompressed stay readable), written
// through AtomicFile, with VTK's error text turned into the exception.
//
//   vtkNew<vtkXMLPolyDataWriter> writer;
//   writer->SetInputData(polydata);
//   fw::io::write_vtk_xml("write_trees_vtp", "out/trees/trees_000003.vtp", writer);
#pragma once

#include <filesystem>

class vtkXMLWriter;

namespace fw::io {

/// Runs `writer` (its input already set) into a temporary next to `path` and renames it into place.
/// Throws std::runtime_error("FUNCTION: cannot write PATH: reason") when the folder does not exist or the
/// write fails, leaving neither the file nor a temporary.
void write_vtk_xml(const char* function, const std::filesystem::path& path, vtkXMLWriter* writer);

}  // namespace fw::io
