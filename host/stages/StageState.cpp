#include "host/stages/StageState.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace fw::host {

void StageState::save(ComputeContext& cc, const std::string& name, cl::Buffer& buffer) {
  std::vector<std::uint8_t>& bytes = buffers[name];
  bytes.resize(buffer.getInfo<CL_MEM_SIZE>());  // the whole allocation
  cc.queue().enqueueReadBuffer(buffer, CL_TRUE, 0, bytes.size(), bytes.data());
}

const std::vector<std::uint8_t>& StageState::bytes(const std::string& stage, const std::string& name) const {
  const auto at = buffers.find(name);
  if (at == buffers.end())
    throw std::invalid_argument(fmt::format("{}: the saved state has no buffer \"{}\"", stage, name));
  return at->second;
}

void StageState::restore(ComputeContext& cc, const std::string& stage, const std::string& name,
                         cl::Buffer& buffer) const {
  const std::vector<std::uint8_t>& saved = bytes(stage, name);
  const std::size_t size = buffer.getInfo<CL_MEM_SIZE>();
  if (saved.size() != size)
    throw std::invalid_argument(fmt::format(
        "{}: the saved buffer \"{}\" holds {} bytes, and this run's holds {}: the state is another run's",
        stage, name, saved.size(), size));
  cc.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, size, saved.data());
}

const std::vector<double>& StageState::number(const std::string& stage, const std::string& name,
                                              std::size_t count) const {
  const auto at = numbers.find(name);
  if (at == numbers.end())
    throw std::invalid_argument(fmt::format("{}: the saved state has no value \"{}\"", stage, name));
  if (at->second.size() != count)
    throw std::invalid_argument(fmt::format("{}: the saved \"{}\" holds {} values, {} expected", stage, name,
                                            at->second.size(), count));
  return at->second;
}

}  // namespace fw::host
