// CanopenDevice's TPDO mapping, shared by every kind of device (issue 20: a mapping the device
// does not let the bench write is read back and used as found).
#include "wavebench/bench/bench_device.hpp"

namespace wavebench::bench {

void CanopenDevice::adopt_tpdos(canopen::SdoClient& sdo,
                                const std::vector<canopen::PdoConfig>& wanted,
                                std::span<const canopen::NeededObject> needed) {
  std::vector<canopen::PdoAdoption> candidates;
  for (std::size_t i = 0; i < wanted.size(); ++i) {
    candidates.push_back(canopen::configure_or_read_back(sdo, canopen::PdoDirection::transmit,
                                                         static_cast<unsigned>(i + 1), wanted[i]));
  }
  adopted_ = canopen::use_tpdos(sdo, std::move(candidates), needed);
}

}  // namespace wavebench::bench
