// The protocol between the ngspice runner and its worker program (emnet-ngspice-worker): one
// definition, used by both sides (ngspice_worker_backend.cpp starts the worker,
// ngspice_worker_main.cpp is the worker).
//
// The runner starts the worker through the process helper (emnet/core/process.hpp) as
//   emnet-ngspice-worker protocol=1 max_message_bytes=BYTES library=NAME [library=NAME ...]
// with the deck on standard input, one line per '\n' (the lines hold no '\n' and no NUL). The
// worker answers with records on its standard output; whatever else it prints (libngspice
// writing to its standard streams directly) goes to its standard error, which the runner keeps
// as ngspice's standard-error lines. Exit status: 0 after the status record, 2 for arguments it
// does not understand (another protocol version: a worker from another build), 3 when the
// worker itself failed.
//
// The record stream, worker to runner, one record after another:
//   tag (1 byte) · payload length (8 bytes) · payload
// with the payload of a vector record
//   flags (1 byte: 1 scale, 2 complex) · name length (4 bytes) · name · count (8 bytes) ·
//   count doubles (real) or count (real, imaginary) pairs
// and of a message record
//   bytes cut from the line (8 bytes) · the line's first bytes (at most kNgspiceMaxLineBytes)
// all in the machine's own byte order: both ends are built from the same sources for the same
// machine, and raw doubles carry every bit. The runner checks each record's length against
// what its tag may hold (a vector: what is left of max_result_bytes) before it keeps a byte of
// it. Records, in order: library loaded (or unavailable, and nothing else), messages as they
// come, plot names, vectors, ngspice's seconds, status.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "emnet/spice/ngspice_runner.hpp"
#include "ngspice_messages.hpp"

namespace emnet {

constexpr const char* kNgspiceWorkerName = "emnet-ngspice-worker";
constexpr int kNgspiceWorkerProtocol = 1;
constexpr int kNgspiceWorkerUsageExitStatus = 2;
constexpr int kNgspiceWorkerFailureExitStatus = 3;

// What the worker is asked to do with the deck it reads.
struct NgspiceWorkerRequest {
  std::vector<std::string> library_names;
  std::size_t max_message_bytes = 0;
};

// The worker's command line (the program's path first).
std::vector<std::string> ngspice_worker_arguments(const std::string& worker_path,
                                                  const NgspiceWorkerRequest& request);
// The worker's side; false with `why` on arguments it does not understand.
bool parse_ngspice_worker_arguments(int argc, const char* const* argv,
                                    NgspiceWorkerRequest& request, std::string& why);
// The deck's lines as the worker's standard input, and back.
std::string ngspice_worker_input(const std::vector<std::string>& lines);
std::vector<std::string> ngspice_worker_deck_lines(const std::string& input);

enum class RecordTag : std::uint8_t {
  message_out = 1,
  message_err = 2,
  library_loaded = 3,       // payload: the library's name
  library_unavailable = 4,  // payload: why
  plot_name = 5,
  vector = 6,
  status = 7,  // payload: ok byte, message
  ngspice_seconds = 8,
};

constexpr std::size_t kRecordHeaderBytes = 1 + sizeof(std::uint64_t);
// The longest payload of a record of text (a library name or why it did not load; a status
// message: at most 20 lines of ngspice's, each at most kNgspiceMaxLineBytes made printable).
constexpr std::size_t kMaxTextRecordBytes = std::size_t{1} << 20;

// At most `limit` bytes of `text`, for a record of text.
std::string cut_to(const std::string& text, std::size_t limit);

// Writes whole records to a descriptor, one at a time (the library's threads write too).
class RecordWriter {
 public:
  explicit RecordWriter(int descriptor) : descriptor_(descriptor) {}
  void write(RecordTag tag, const std::string& payload);

 private:
  int descriptor_;
  std::mutex mutex_;
};

std::string encode_vector(const NgspiceVector& vector);
// A message record's payload: the count of bytes cut, then at most kNgspiceMaxLineBytes.
std::string encode_message(const std::string& text);
std::string encode_seconds(double seconds);
std::string encode_status(const Status& status);

// False on a malformed payload. A vector's name and a status message come back made
// printable; a message line is made printable by the MessageLog it goes to.
bool decode_vector(const std::string& payload, NgspiceVector& vector);
bool decode_message(const std::string& payload, std::string& line, std::uint64_t& bytes_cut);
bool decode_seconds(const std::string& payload, double& seconds);
bool decode_status(const std::string& payload, Status& status);

// The worker's records, decoded as they arrive: the buffer holds at most one record (and
// one read), and each record's claimed length is checked against what its tag may hold before
// any byte of it is kept; the vectors together may hold at most `result_byte_limit` bytes.
class RecordReader {
 public:
  explicit RecordReader(std::uint64_t result_byte_limit)
      : result_byte_limit_(result_byte_limit), result_bytes_left_(result_byte_limit) {}

  // Adds bytes and calls `handle(tag, payload)` for each record they complete. False, with
  // `problem()`, when a record breaks the rules; the stream is then unusable.
  template <class Handle>
  bool add(const char* data, std::size_t size, Handle&& handle) {
    buffer_.append(data, size);
    std::size_t position = 0;
    bool ok = true;
    while (buffer_.size() - position >= kRecordHeaderBytes) {
      const auto tag = static_cast<RecordTag>(buffer_[position]);
      std::uint64_t length;
      std::memcpy(&length, buffer_.data() + position + 1, sizeof length);
      if (!allowed(tag, length)) {
        ok = false;
        break;
      }
      if (buffer_.size() - position - kRecordHeaderBytes < length) break;
      if (tag == RecordTag::vector) result_bytes_left_ -= length;
      handle(tag, buffer_.substr(position + kRecordHeaderBytes, length));
      position += kRecordHeaderBytes + length;
    }
    buffer_.erase(0, position);
    return ok;
  }
  const std::string& problem() const { return problem_; }

 private:
  bool allowed(RecordTag tag, std::uint64_t length);
  std::uint64_t result_byte_limit_, result_bytes_left_;
  std::string buffer_;
  std::string problem_;
};

}  // namespace emnet
