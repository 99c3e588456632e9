// FFTW plan creation and destruction are not thread-safe (fftw_execute is): every analysis
// in this module creates/destroys plans under this one lock.
#pragma once

#include <mutex>

namespace stickslip::detail {
std::mutex& fftwPlanMutex();
}  // namespace stickslip::detail
