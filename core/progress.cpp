#include "core/progress.hpp"

#include <csignal>

namespace fibermold {

namespace {
volatile std::sig_atomic_t g_interrupt = 0;
} // namespace

void request_interrupt() noexcept { g_interrupt = 1; }
bool interrupt_requested() noexcept { return g_interrupt != 0; }
void clear_interrupt() noexcept { g_interrupt = 0; }

bool Progress::interrupted() const { return interrupt_requested(); }

void Progress::checkpoint(double fraction, std::string_view what)
{
  update(fraction, what);
  if (interrupted()) throw Interrupted();
}

} // namespace fibermold
