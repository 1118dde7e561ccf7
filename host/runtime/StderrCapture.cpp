#include "host/runtime/StderrCapture.hpp"

#include <unistd.h>

#include <cstdio>

namespace fw::host {

StderrCapture::StderrCapture() {
  std::FILE* file = std::tmpfile();  // unlinked already: nothing is left behind whatever happens
  if (!file) return;
  captured_ = dup(fileno(file));
  std::fclose(file);
  if (captured_ < 0) return;
  std::fflush(stderr);
  saved_ = dup(STDERR_FILENO);
  if (saved_ < 0 || dup2(captured_, STDERR_FILENO) < 0) {
    if (saved_ >= 0) close(saved_);
    close(captured_);
    saved_ = captured_ = -1;
  }
}

StderrCapture::~StderrCapture() {
  release();
}

std::string StderrCapture::release() {
  if (saved_ < 0) return {};
  std::fflush(stderr);
  dup2(saved_, STDERR_FILENO);
  close(saved_);
  saved_ = -1;
  std::string text;
  char chunk[4096];
  ssize_t got = 0;
  for (off_t at = 0; (got = pread(captured_, chunk, sizeof chunk, at)) > 0; at += got)
    text.append(chunk, got);
  close(captured_);
  captured_ = -1;
  return text;
}

}  // namespace fw::host
