// The runner–worker protocol: command line, deck, records; see ngspice_worker_protocol.hpp.
#include "ngspice_worker_protocol.hpp"

#include <charconv>
#include <complex>
#include <cstring>

#include "core/posix_handles.hpp"
#include "emnet/core/terminal_text.hpp"

namespace emnet {

namespace {

// The worker's arguments are words NAME=VALUE of the runner–worker protocol (no front-end's
// options: the worker is started by the library only).
constexpr const char* kProtocolWord = "protocol";
constexpr const char* kMaxMessageBytesWord = "max_message_bytes";
constexpr const char* kLibraryWord = "library";

std::string word(const char* name, const std::string& value) {
  return std::string(name) + "=" + value;
}

template <class T>
void append_raw(std::string& bytes, const T& value) {
  bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <class T>
bool read_raw(const std::string& bytes, std::size_t& position, T& value) {
  if (bytes.size() - position < sizeof value) return false;
  std::memcpy(&value, bytes.data() + position, sizeof value);
  position += sizeof value;
  return true;
}

template <class Number>
bool parse_number(const char* text, Number& number) {
  const char* end = text + std::strlen(text);
  const auto [stop, error] = std::from_chars(text, end, number);
  return error == std::errc() && stop == end && stop != text;
}

}  // namespace

// ---- command line and deck ------------------------------------------------------------------

std::vector<std::string> ngspice_worker_arguments(const std::string& worker_path,
                                                  const NgspiceWorkerRequest& request) {
  std::vector<std::string> arguments = {
      worker_path, word(kProtocolWord, std::to_string(kNgspiceWorkerProtocol)),
      word(kMaxMessageBytesWord, std::to_string(request.max_message_bytes))};
  for (const std::string& name : request.library_names)
    arguments.push_back(word(kLibraryWord, name));
  return arguments;
}

bool parse_ngspice_worker_arguments(int argc, const char* const* argv,
                                    NgspiceWorkerRequest& request, std::string& why) {
  bool have_protocol = false, have_limit = false;
  for (int index = 1; index < argc; ++index) {
    const std::string argument = argv[index];
    const std::size_t equals = argument.find('=');
    if (equals == std::string::npos) {
      why = "argument '" + argument + "' is not NAME=VALUE";
      return false;
    }
    const std::string option = argument.substr(0, equals);
    const char* value = argv[index] + equals + 1;
    if (option == kProtocolWord) {
      int protocol = 0;
      if (!parse_number(value, protocol) || protocol != kNgspiceWorkerProtocol) {
        why = "asked for protocol " + std::string(value) + "; this worker speaks protocol " +
              std::to_string(kNgspiceWorkerProtocol) + " (it belongs to another build of emnet)";
        return false;
      }
      have_protocol = true;
    } else if (option == kMaxMessageBytesWord) {
      if (!parse_number(value, request.max_message_bytes)) {
        why = "bad " + option + " value '" + value + "'";
        return false;
      }
      have_limit = true;
    } else if (option == kLibraryWord) {
      request.library_names.emplace_back(value);
    } else {
      why = "unknown argument " + option;
      return false;
    }
  }
  if (!have_protocol || !have_limit) {
    why = std::string("usage: ") + kNgspiceWorkerName + " " +
          word(kProtocolWord, std::to_string(kNgspiceWorkerProtocol)) + " " +
          word(kMaxMessageBytesWord, "BYTES") + " [" + word(kLibraryWord, "NAME") +
          " ...] < DECK (started by emnet's ngspice runner)";
    return false;
  }
  return true;
}

std::string ngspice_worker_input(const std::vector<std::string>& lines) {
  std::string input;
  for (const std::string& line : lines) input += line + '\n';
  return input;
}

std::vector<std::string> ngspice_worker_deck_lines(const std::string& input) {
  std::vector<std::string> lines;
  for (std::size_t begin = 0; begin < input.size();) {
    std::size_t end = input.find('\n', begin);
    if (end == std::string::npos) end = input.size();
    lines.push_back(input.substr(begin, end - begin));
    begin = end + 1;
  }
  return lines;
}

// ---- records --------------------------------------------------------------------------------

std::string cut_to(const std::string& text, std::size_t limit) {
  return text.size() <= limit ? text : text.substr(0, limit);
}

void RecordWriter::write(RecordTag tag, const std::string& payload) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t length = payload.size();
  std::string record(1, static_cast<char>(tag));
  record.append(reinterpret_cast<const char*>(&length), sizeof length);
  write_fully(descriptor_, record.data(), record.size());
  write_fully(descriptor_, payload.data(), payload.size());
}

std::string encode_vector(const NgspiceVector& vector) {
  std::string bytes;
  append_raw(bytes,
             static_cast<std::uint8_t>((vector.is_scale ? 1 : 0) | (vector.is_complex ? 2 : 0)));
  append_raw(bytes, static_cast<std::uint32_t>(vector.name.size()));
  bytes += vector.name;
  append_raw(bytes, static_cast<std::uint64_t>(vector.size()));
  if (vector.is_complex)
    bytes.append(reinterpret_cast<const char*>(vector.complex_values.data()),
                 vector.complex_values.size() * sizeof(std::complex<double>));
  else
    bytes.append(reinterpret_cast<const char*>(vector.real_values.data()),
                 vector.real_values.size() * sizeof(double));
  return bytes;
}

std::string encode_message(const std::string& text) {
  std::string bytes;
  const std::size_t kept = std::min(text.size(), kNgspiceMaxLineBytes);
  append_raw(bytes, static_cast<std::uint64_t>(text.size() - kept));
  bytes.append(text, 0, kept);
  return bytes;
}

std::string encode_seconds(double seconds) {
  std::string bytes;
  append_raw(bytes, seconds);
  return bytes;
}

std::string encode_status(const Status& status) {
  return std::string(1, status.ok() ? '\1' : '\0') + cut_to(status.message, kMaxTextRecordBytes);
}

bool decode_vector(const std::string& bytes, NgspiceVector& vector) {
  std::size_t position = 0;
  std::uint8_t flags;
  std::uint32_t name_length;
  std::uint64_t count;
  if (!read_raw(bytes, position, flags) || !read_raw(bytes, position, name_length) ||
      bytes.size() - position < name_length)
    return false;
  vector.name = terminal_text(std::string_view(bytes).substr(position, name_length));
  position += name_length;
  if (!read_raw(bytes, position, count)) return false;
  vector.is_scale = (flags & 1) != 0;
  vector.is_complex = (flags & 2) != 0;
  const std::size_t element = vector.is_complex ? sizeof(std::complex<double>) : sizeof(double);
  // The count is checked against the payload's actual size before anything is allocated.
  if ((bytes.size() - position) / element != count || (bytes.size() - position) % element != 0)
    return false;
  if (vector.is_complex) {
    vector.complex_values.resize(count);
    std::memcpy(vector.complex_values.data(), bytes.data() + position, count * element);
  } else {
    vector.real_values.resize(count);
    std::memcpy(vector.real_values.data(), bytes.data() + position, count * element);
  }
  return true;
}

bool decode_message(const std::string& payload, std::string& line, std::uint64_t& bytes_cut) {
  std::size_t position = 0;
  if (!read_raw(payload, position, bytes_cut)) return false;
  line = payload.substr(position);
  return true;
}

bool decode_seconds(const std::string& payload, double& seconds) {
  std::size_t position = 0;
  return payload.size() == sizeof seconds && read_raw(payload, position, seconds);
}

bool decode_status(const std::string& payload, Status& status) {
  if (payload.empty()) return false;
  status = payload[0] ? Status::success() : Status::failure(terminal_text(payload.substr(1)));
  return true;
}

bool RecordReader::allowed(RecordTag tag, std::uint64_t length) {
  std::uint64_t limit = 0;
  switch (tag) {
    case RecordTag::message_out:
    case RecordTag::message_err:
      limit = sizeof(std::uint64_t) + kNgspiceMaxLineBytes;
      break;
    case RecordTag::plot_name:
      limit = kNgspiceMaxLineBytes;
      break;
    case RecordTag::library_loaded:
    case RecordTag::library_unavailable:
    case RecordTag::status:
      limit = kMaxTextRecordBytes + 1;
      break;
    case RecordTag::ngspice_seconds:
      limit = sizeof(double);
      break;
    case RecordTag::vector:
      if (length > result_bytes_left_) {
        problem_ = "ngspice's results are larger than max_result_bytes (" +
                   std::to_string(result_byte_limit_) + " bytes)";
        return false;
      }
      return true;
    default:
      problem_ = "the ngspice worker sent a record of unknown kind " +
                 std::to_string(static_cast<int>(tag));
      return false;
  }
  if (length <= limit) return true;
  problem_ = "the ngspice worker sent a record of kind " + std::to_string(static_cast<int>(tag)) +
             " of " + std::to_string(length) + " bytes, more than the " + std::to_string(limit) +
             " it may hold";
  return false;
}

}  // namespace emnet
