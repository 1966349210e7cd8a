// Reading whole OpenIGTLink messages from a socket with a receive timeout: igtl::Socket::Receive
// may return part of the bytes asked for once a timeout is set, so the rest is read on.
// Shared by the device's network thread and the tests' OpenIGTLink client.
#pragma once

#include <igtlMessageHeader.h>
#include <igtlSocket.h>

namespace tacta::igtl_device {

enum class Received { kMessage, kNothing, kClosed };

// Reads exactly `length` bytes; a timeout before the first byte is kNothing, a peer that closes
// or stalls for `patience` timeouts in mid-message is kClosed.
inline Received receive_fully(igtl::Socket& socket, void* data, int length, int patience = 1000) {
  auto* bytes = static_cast<unsigned char*>(data);
  int total = 0;
  while (total < length) {
    const int n = socket.Receive(bytes + total, length - total);
    if (n == 0) return Received::kClosed;
    if (n < 0) {
      if (total == 0) return Received::kNothing;
      if (--patience <= 0) return Received::kClosed;
      continue;
    }
    total += n;
  }
  return Received::kMessage;
}

// The next message's header (unpacked), kNothing on a timeout.
inline Received receive_header(igtl::Socket& socket, igtl::MessageHeader::Pointer& header) {
  header->InitPack();
  const Received r =
      receive_fully(socket, header->GetPackPointer(), static_cast<int>(header->GetPackSize()));
  if (r == Received::kMessage) header->Unpack();
  return r;
}

// The body of the message whose header was just read, into `message` (unpacked with its CRC
// checked). False when the connection failed or the body is corrupt.
template <class Message>
bool receive_body(igtl::Socket& socket, const igtl::MessageHeader::Pointer& header,
                  Message& message, bool& closed) {
  message->SetMessageHeader(header);
  message->AllocatePack();
  Received r = Received::kNothing;
  for (int wait = 0; wait < 1000 && r == Received::kNothing; ++wait)  // the body follows its header
    r = receive_fully(socket, message->GetPackBodyPointer(),
                      static_cast<int>(message->GetPackBodySize()));
  closed = r != Received::kMessage;
  if (closed) return false;
  return (message->Unpack(1) & igtl::MessageHeader::UNPACK_BODY) != 0;
}

}  // namespace tacta::igtl_device
