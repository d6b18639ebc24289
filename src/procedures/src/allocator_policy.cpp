#include "wavebench/procedures/allocator_policy.hpp"

#include <malloc.h>

namespace wavebench::procedures {

void use_allocator_policy() noexcept {
  // Setting it also turns off glibc's dynamic adjustment (mallopt(3)).
  mallopt(M_MMAP_THRESHOLD, 128 * 1024);
}

}  // namespace wavebench::procedures
