// Bands.h: a loop over rows split in two bands, the lower one on a second thread, for passes
// over a picture or a texture level that are large enough to pay for the thread and leave the
// host's other core idle (the readback's NaN check, the host's mip levels).
#pragma once

#include <system_error>
#include <thread>

namespace lantern {

/// Runs band(begin, end) over the rows [0, rows): as [0, rows / 2) here and [rows / 2, rows) on
/// a second thread when `split` is true, there are at least two rows and the host has a second
/// core; else band(0, rows) here. A thread that cannot be started leaves its band to this one.
/// The bands may run in either order and at once.
template <typename Band>
void inTwoBands(int rows, bool split, Band&& band) {
    static const bool twoCores = std::thread::hardware_concurrency() > 1;  // read once
    if (!split || !twoCores || rows < 2) {
        band(0, rows);
        return;
    }
    const int half = rows / 2;
    std::thread other;
    try {
        other = std::thread([&] { band(half, rows); });
    } catch (const std::system_error&) {  // no thread to be had: both bands here
    }
    band(0, half);
    if (other.joinable())
        other.join();
    else
        band(half, rows);
}

} // namespace lantern
