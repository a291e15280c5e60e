#include "support/text_channel.h"

namespace clpc {

void TextChannel::push(std::string_view text) {
  if (text.empty()) return;
  std::unique_lock<std::mutex> g(lock_);
  changed_.wait(g, [&] { return abandoned_ || full_.size() < kChunks; });
  if (abandoned_) return;
  std::string chunk;
  if (!spare_.empty()) {
    chunk = std::move(spare_.back());
    spare_.pop_back();
  }
  chunk.assign(text);
  full_.push_back(std::move(chunk));
  g.unlock();
  changed_.notify_all();
}

void TextChannel::close() {
  {
    std::lock_guard<std::mutex> g(lock_);
    closed_ = true;
  }
  changed_.notify_all();
}

bool TextChannel::pop(std::string& out) {
  std::unique_lock<std::mutex> g(lock_);
  changed_.wait(g, [&] { return closed_ || !full_.empty(); });
  if (full_.empty()) return false;
  out.clear();
  if (out.capacity() > 0) spare_.push_back(std::move(out));
  out = std::move(full_.front());
  full_.pop_front();
  g.unlock();
  changed_.notify_all();
  return true;
}

void TextChannel::abandon() {
  {
    std::lock_guard<std::mutex> g(lock_);
    abandoned_ = true;
    full_.clear();
  }
  changed_.notify_all();
}

}  // namespace clpc
