#pragma once
// Exclusive use of Coin3D for one load or save. Coin keeps global state (its type system, its
// error handlers, its name dictionary), so palpate serialises its own use of it behind one
// process-wide lock, initialises it once (SoDB::init) and, while it holds the lock, collects Coin's
// read errors and debug messages instead of letting Coin print them. The previous handlers are
// restored when the session ends.
#include <Inventor/errors/SoError.h>

#include <mutex>
#include <string>
#include <vector>

namespace palpate::detail {

class CoinSession {
 public:
  struct ReadError {
    int line = 0;         // 0 where Coin gave none
    std::string message;  // Coin's own words, without its "Coin read error:" prefix and location
  };

  CoinSession();
  ~CoinSession();
  CoinSession(const CoinSession&) = delete;
  CoinSession& operator=(const CoinSession&) = delete;

  std::vector<ReadError> read_errors;
  std::vector<std::string> messages;  // Coin's other errors, warnings and notes

 private:
  static void on_read_error(const SoError* error, void* session);
  static void on_other_error(const SoError* error, void* session);

  std::unique_lock<std::mutex> lock_;
  SoErrorCB* saved_read_handler_ = nullptr;
  void* saved_read_data_ = nullptr;
  SoErrorCB* saved_debug_handler_ = nullptr;
  void* saved_debug_data_ = nullptr;
  SoErrorCB* saved_error_handler_ = nullptr;
  void* saved_error_data_ = nullptr;
};

}  // namespace palpate::detail
