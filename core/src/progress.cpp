#include "corsa/core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace corsa {

bool is_terminal(std::FILE* stream) { return ::isatty(::fileno(stream)) == 1; }

ProgressBar::ProgressBar(std::string label, double total, bool enabled, std::FILE* stream)
    : label_(std::move(label)),
      total_(total),
      visible_(enabled && is_terminal(stream)),
      stream_(stream),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::update(double done) {
  std::lock_guard lock(mutex_);
  done_ = done;
  draw_locked(false);
}

void ProgressBar::advance(double amount) {
  std::lock_guard lock(mutex_);
  done_ += amount;
  draw_locked(false);
}

void ProgressBar::set_total(double total) {
  std::lock_guard lock(mutex_);
  total_ = total;
}

void ProgressBar::restart(std::string label, double total) {
  std::lock_guard lock(mutex_);
  label_ = std::move(label);
  total_ = total;
  done_ = 0.0;
  finished_ = false;
  start_ = std::chrono::steady_clock::now();
  last_draw_ = start_ - std::chrono::seconds(1);
}

void ProgressBar::complete() {
  {
    std::lock_guard lock(mutex_);
    done_ = total_;
  }
  finish();
}

void ProgressBar::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) {
    return;
  }
  finished_ = true;
  if (visible_) {
    draw_locked(true);
    std::fputc('\n', stream_);
    std::fflush(stream_);
  }
}

void ProgressBar::draw_locked(bool force) {
  if (!visible_ || (finished_ && !force)) {
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (!force && now - last_draw_ < std::chrono::milliseconds(100)) {
    return;
  }
  last_draw_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const std::string line = render(label_, done_, total_, elapsed, 30);
  std::fprintf(stream_, "\r%s\x1b[K", line.c_str());
  std::fflush(stream_);
}

std::string ProgressBar::render(const std::string& label, double done, double total,
                                double elapsed_seconds, int width) {
  const double fraction = total > 0.0 ? std::clamp(done / total, 0.0, 1.0) : 0.0;
  const int filled = static_cast<int>(std::lround(fraction * width));
  std::ostringstream out;
  out << label << " [" << std::string(filled, '#') << std::string(width - filled, '-') << "] ";
  out.setf(std::ios::fixed);
  out.precision(0);
  out << fraction * 100.0 << '%';
  if (fraction > 0.0 && fraction < 1.0 && elapsed_seconds > 0.0) {
    const double eta = elapsed_seconds * (1.0 - fraction) / fraction;
    out.precision(eta < 10.0 ? 1 : 0);
    out << " ETA " << eta << 's';
  } else if (fraction >= 1.0) {
    out.precision(elapsed_seconds < 10.0 ? 2 : 0);
    out << " done in " << elapsed_seconds << 's';
  }
  return out.str();
}

}  // namespace corsa
