#include "core/coin_session.hpp"

#include <Inventor/SoDB.h>
#include <Inventor/errors/SoDebugError.h>
#include <Inventor/errors/SoReadError.h>

#include <cctype>
#include <cstdlib>
#include <string_view>

namespace palpate::detail {
namespace {

std::mutex& coin_mutex() {
  static std::mutex mutex;
  return mutex;
}

// Coin formats a read error as "Coin read error: <what>\n\tOccurred at line <n> in <source>".
CoinSession::ReadError parse_read_error(const std::string& text) {
  constexpr std::string_view prefix = "Coin read error: ", located = "Occurred at line";
  CoinSession::ReadError error;
  error.message = text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : text;
  if (const std::size_t at = error.message.find(located); at != std::string::npos) {
    error.line = std::atoi(error.message.c_str() + at + located.size());  // atoi skips the padding
    error.message.erase(at);
  }
  while (!error.message.empty() && std::isspace(static_cast<unsigned char>(error.message.back())))
    error.message.pop_back();
  return error;
}

}  // namespace

CoinSession::CoinSession() : lock_(coin_mutex()) {
  if (!SoDB::isInitialized()) SoDB::init();  // under the lock: once per process
  saved_read_handler_ = SoReadError::getHandlerCallback();
  saved_read_data_ = SoReadError::getHandlerData();
  saved_debug_handler_ = SoDebugError::getHandlerCallback();
  saved_debug_data_ = SoDebugError::getHandlerData();
  saved_error_handler_ = SoError::getHandlerCallback();
  saved_error_data_ = SoError::getHandlerData();
  SoReadError::setHandlerCallback(&CoinSession::on_read_error, this);
  SoDebugError::setHandlerCallback(&CoinSession::on_other_error, this);
  SoError::setHandlerCallback(&CoinSession::on_other_error, this);
}

CoinSession::~CoinSession() {
  SoReadError::setHandlerCallback(saved_read_handler_, saved_read_data_);
  SoDebugError::setHandlerCallback(saved_debug_handler_, saved_debug_data_);
  SoError::setHandlerCallback(saved_error_handler_, saved_error_data_);
}

void CoinSession::on_read_error(const SoError* error, void* session) {
  static_cast<CoinSession*>(session)->read_errors.push_back(
      parse_read_error(error->getDebugString().getString()));
}

void CoinSession::on_other_error(const SoError* error, void* session) {
  static_cast<CoinSession*>(session)->messages.emplace_back(error->getDebugString().getString());
}

}  // namespace palpate::detail
