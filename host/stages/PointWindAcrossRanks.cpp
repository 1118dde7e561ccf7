#include "host/stages/PointWindAcrossRanks.hpp"

#include <algorithm>
#include <array>

#include "host/runtime/Communicator.hpp"

namespace fw::host {

int PointWindAcrossRanks::holder(const fluid::GridSpec& spec, const fluid::Decomposition& decomposition,
                                 const float point[3]) {
  // The domain's cell, not the block's: a block's grid keeps the domain's origin.
  const std::array<int, 3> cell = spec.domain_cell_holding({point[0], point[1], point[2]});
  return decomposition.rank_holding(cell[0], cell[1]);
}

PointWindAcrossRanks::PointWindAcrossRanks(ComputeContext& cc, const fluid::GridSpec& spec,
                                           const WindBlocks* blocks, const std::vector<float>& needed)
    : world_(blocks != nullptr ? blocks->world : &Communicator::alone()) {
  const int ranks = world_->size();
  const std::size_t count = needed.size() / 3;
  holder_of_.assign(count, world_->rank());
  std::vector<std::vector<float>> asked(static_cast<std::size_t>(ranks));
  order_.resize(count);
  for (std::size_t n = 0; n < count; ++n) {
    if (blocks != nullptr && ranks > 1) holder_of_[n] = holder(spec, blocks->decomposition, &needed[3 * n]);
    auto& list = asked[std::size_t(holder_of_[n])];
    order_[n] = int(list.size() / 3);
    list.insert(list.end(), needed.begin() + std::ptrdiff_t(3 * n),
                needed.begin() + std::ptrdiff_t(3 * n + 3));
  }
  const std::vector<std::vector<float>> requests = world_->exchange(asked);
  std::vector<float> flat;
  for (const auto& list : requests) {
    request_counts_.push_back(int(list.size() / 3));
    flat.insert(flat.end(), list.begin(), list.end());
  }
  requests_ = std::make_unique<PointWindReadback>(cc, spec, std::move(flat));
}

std::vector<float> PointWindAcrossRanks::exchange(DeviceVelocity& velocity) {
  const std::vector<float> sampled = requests_->sample_flat(velocity);
  std::vector<std::vector<float>> answers(request_counts_.size());
  std::size_t at = 0;
  for (std::size_t r = 0; r < answers.size(); ++r) {
    const std::size_t floats = 3 * std::size_t(request_counts_[r]);
    answers[r].assign(sampled.begin() + std::ptrdiff_t(at), sampled.begin() + std::ptrdiff_t(at + floats));
    at += floats;
  }
  const std::vector<std::vector<float>> answered = world_->exchange(answers);
  std::vector<float> wind(3 * order_.size());
  for (std::size_t n = 0; n < order_.size(); ++n) {
    const std::vector<float>& from = answered[std::size_t(holder_of_[n])];
    std::copy_n(from.begin() + 3 * std::ptrdiff_t(order_[n]), 3, wind.begin() + 3 * std::ptrdiff_t(n));
  }
  return wind;
}

}  // namespace fw::host
