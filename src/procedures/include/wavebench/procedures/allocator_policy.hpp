#pragma once
// How the process allocates large buffers, set once at start by the programs that run runs
// (wavebench, wavebenchd).
//
// glibc raises its mmap threshold each time an mmapped block is freed (up to 32 MiB), after
// which a run's large, short-lived buffers (a calibration's rows, a page of samples, the order
// grid) come from the heaps of several threads and stay resident as fragments: a 10-revolution
// dynamic run peaked at 103 MB RSS with 54 MB of heap in use. A fixed threshold keeps every
// block from 128 KiB up in its own mapping, returned to the OS when freed (78 MB RSS).

namespace wavebench::procedures {

void use_allocator_policy() noexcept;

}  // namespace wavebench::procedures
