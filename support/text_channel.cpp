#include "support/text_channel.h"

namespace clpc {

void TextChannel::push(std::string_view text) {
  if (text.empty()) return;
  std::unique_lock<std::mutex> g(lock_);
  handoff_.wait_for_room(g, [&] { return full_.size(); }, [&] { return abandoned_; });
  if (abandoned_) return;
  std::string chunk;
  if (!spare_.empty()) {
    chunk = std::move(spare_.back());
    spare_.pop_back();
  }
  chunk.assign(text);
  full_.push_back(std::move(chunk));
  handoff_.added(g, full_.size());
}

void TextChannel::close() {
  {
    std::lock_guard<std::mutex> g(lock_);
    closed_ = true;
  }
  handoff_.wake_both();
}

bool TextChannel::pop(std::string& out) {
  std::unique_lock<std::mutex> g(lock_);
  handoff_.wait_for_items(g, [&] { return full_.size(); }, [&] { return closed_; });
  if (full_.empty()) return false;
  out.clear();
  if (out.capacity() > 0) spare_.push_back(std::move(out));
  out = std::move(full_.front());
  full_.pop_front();
  handoff_.taken(g, full_.size());
  return true;
}

void TextChannel::abandon() {
  {
    std::lock_guard<std::mutex> g(lock_);
    abandoned_ = true;
    full_.clear();
  }
  handoff_.wake_both();
}

}  // namespace clpc
