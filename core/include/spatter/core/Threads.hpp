#pragma once
// The thread counts the core's parallel steps take.

namespace spatter {

// The most threads one parallel step of the core uses: a proxy build's judgements and certificate, a
// Hausdorff bound, the drawn normals, a deforming object's poses. A setting that takes a thread count
// (ProxySettings::threads, HausdorffSettings::threads) accepts 0, the hardware's at most this, to this.
inline constexpr unsigned kMaxThreads = 16;

} // namespace spatter
