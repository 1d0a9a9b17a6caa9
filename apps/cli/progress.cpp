#include "progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace sonarmap::cli {

ProgressBar::ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(fileno(stderr)) != 0) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\r\033[K", stderr);  // leave the line clean for the summary
}

void ProgressBar::update(std::size_t done, std::size_t total) {
  if (!enabled_ || total == 0) return;
  constexpr int kWidth = 30;
  const std::size_t per_mille = std::min<std::size_t>(done, total) * 1000 / total;
  if (drawn_ && per_mille == last_per_mille_) return;  // redraw only when the bar moves by 0.1 %
  last_per_mille_ = per_mille;
  const int filled = static_cast<int>(kWidth * std::min(done, total) / total);
  std::fprintf(stderr, "\r%s [%.*s%*s] %zu/%zu", label_.c_str(), filled, "##############################",
               kWidth - filled, "", done, total);
  std::fflush(stderr);
  drawn_ = true;
}

}  // namespace sonarmap::cli
