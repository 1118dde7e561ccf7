#include "io/VtkXml.hpp"

#include <fmt/format.h>

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkErrorCode.h>
#include <vtkExecutive.h>
#include <vtkNew.h>
#include <vtkXMLWriter.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "base/AtomicFile.hpp"

namespace fw::io {
namespace {

// Keeps VTK's error text (instead of printing it on stderr) so that it can go into the exception.
void keep_error_text(vtkObject* /*caller*/, unsigned long /*event*/, void* client, void* call) {
  auto* text = static_cast<std::string*>(client);
  std::string message = call ? static_cast<const char*>(call) : "unknown VTK error";
  // VTK 9.1: "ERROR: In FILE, line N\nCLASS (ADDRESS): message\n\n". Only the message is useful to a user.
  if (message.rfind("ERROR: In ", 0) == 0) {
    if (const auto newline = message.find('\n'); newline != std::string::npos) message.erase(0, newline + 1);
  }
  if (const auto colon = message.find("): "); colon != std::string::npos && colon < message.find('\n')) {
    message.erase(0, colon + 3);
  }
  while (!message.empty() && (message.back() == '\n' || message.back() == ' ')) message.pop_back();
  if (!text->empty()) *text += "; ";
  *text += message;
}

// vtkErrorCode::GetStringFromErrorCode is in VTK::CommonMisc (not linked); the enum itself is header-only.
std::string error_code_text(unsigned long code) {
  if (code == vtkErrorCode::CannotOpenFileError) return "cannot open the file";
  if (code == vtkErrorCode::OutOfDiskSpaceError) return "out of disk space";
  if (code == vtkErrorCode::NoFileNameError) return "no file name";
  if (code > 0 && code < vtkErrorCode::FirstVTKErrorCode) return std::strerror(int(code));
  return fmt::format("VTK error code {}", code);
}

}  // namespace

void write_vtk_xml(const char* function, const std::filesystem::path& path, vtkXMLWriter* writer) {
  base::require_output_folder(function, path);
  base::AtomicFile file(path);
  const std::string temporary = file.temporary_path().string();
  writer->SetFileName(temporary.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();  // raw bytes after <AppendedData>, not base64
  // LZ4: about 20x faster than zlib on our float fields for a quarter more bytes (float mantissas barely
  // compress either way); ParaView 5.11 reads it.
  writer->SetCompressorTypeToLZ4();
  writer->SetHeaderTypeToUInt64();  // frames over 4 GiB uncompressed stay readable

  std::string messages;
  vtkNew<vtkCallbackCommand> on_error;
  on_error->SetCallback(keep_error_text);
  on_error->SetClientData(&messages);
  writer->AddObserver(vtkCommand::ErrorEvent, on_error);
  // The executive repeats a failure with a dump of the pipeline request: keep it off stderr, and use its
  // first line only when nothing better was said.
  std::string pipeline_messages;
  vtkNew<vtkCallbackCommand> on_pipeline_error;
  on_pipeline_error->SetCallback(keep_error_text);
  on_pipeline_error->SetClientData(&pipeline_messages);
  writer->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, on_pipeline_error);

  errno = 0;  // VTK's error codes do not say why a stream failed; the failing write(2)'s errno does
  const int written = writer->Write();
  const int write_errno = errno;
  const unsigned long code = writer->GetErrorCode();
  writer->RemoveObservers(vtkCommand::ErrorEvent);
  writer->GetExecutive()->RemoveObservers(vtkCommand::ErrorEvent);
  if (written == 0 || code != vtkErrorCode::NoError || !messages.empty()) {
    std::string reason = messages;
    if (reason.empty() && code != vtkErrorCode::NoError) reason = error_code_text(code);
    // A failed stream: the system's reason first ("No space left on device"), then VTK's words.
    if (write_errno != 0 &&
        (code == vtkErrorCode::OutOfDiskSpaceError || code == vtkErrorCode::CannotOpenFileError))
      reason = reason.empty() ? std::strerror(write_errno)
                              : fmt::format("{} ({})", std::strerror(write_errno), reason);
    if (reason.empty()) reason = pipeline_messages.substr(0, pipeline_messages.find('\n'));
    if (reason.empty()) reason = "the VTK writer failed";
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), reason));
  }
  try {
    file.commit();
  } catch (const std::runtime_error& error) {
    throw std::runtime_error(fmt::format("{}: cannot write {}: {}", function, path.string(), error.what()));
  }
}

}  // namespace fw::io
