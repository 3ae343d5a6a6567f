// SPDX-License-Identifier: MIT
// Modbus/TCP throughput and cycle cost.
//   BM_Server/{fc}/{clients}: requests per second (items_per_second) of our simulated drive
//     server with 1 and 8 libmodbus clients (one thread and one connection each), FC 3 (read 6
//     registers) and FC 16 (write 4 registers).
//   BM_LibmodbusSelectServer/{fc}/{clients}: the same clients against a plain single-threaded
//     libmodbus select() server (modbus_receive/modbus_reply), the baseline to beat.
//   BM_CycleReadWrite: what a Modbus axis costs the motion thread, read() + write() of a
//     free-running ModbusDrive exchanging with our server (1 ms poll period).
//   BM_HandleRequest: check_request + libmodbus' modbus_reply() + device for one FC 23 cycle request.
// Run: bench_modbus --benchmark_format=json
#include <benchmark/benchmark.h>
#include <modbus.h>
#include <netinet/in.h>
#include <sys/select.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <thread>
#include <vector>

#include "hil/drives/modbus_drive.hpp"
#include "hil/mocks/modbus_server.hpp"
#include "hil/modbus/profile.hpp"

namespace {

using namespace hil;

constexpr int kRequestsPerClient = 4000;

modbus::Profile profile() {
  auto p = modbus::load_profile(HIL_MODBUS_PROFILE_DIR "/cia402.yaml");
  if (!p) std::abort();
  return *p;
}

// N client threads, each kRequestsPerClient requests on its own connection. Returns failures.
int run_clients(std::uint16_t port, int clients, int fc) {
  std::atomic<int> failures{0};
  std::vector<std::thread> threads;
  for (int c = 0; c < clients; ++c) {
    threads.emplace_back([&] {
      modbus_t* ctx = modbus_new_tcp("127.0.0.1", port);
      if (!ctx || modbus_connect(ctx) != 0) {
        failures += kRequestsPerClient;
        if (ctx) modbus_free(ctx);
        return;
      }
      std::uint16_t regs[8] = {0x0F, 8, 0, 100, 0, 0, 0, 0};
      for (int i = 0; i < kRequestsPerClient; ++i) {
        const int rc = fc == 3 ? modbus_read_registers(ctx, 10, 6, regs) : modbus_write_registers(ctx, 2, 4, regs);
        if (rc < 0) ++failures;
      }
      modbus_close(ctx);
      modbus_free(ctx);
    });
  }
  for (auto& t : threads) t.join();
  return failures.load();
}

void BM_Server(benchmark::State& state) {
  const int fc = static_cast<int>(state.range(0));
  const int clients = static_cast<int>(state.range(1));
  mocks::ModbusDriveServer server(mocks::DriveDevice(profile()), {});
  if (server.start()) {
    state.SkipWithError("server did not start");
    return;
  }
  int failures = 0;
  for (auto _ : state) failures += run_clients(server.port(), clients, fc);
  server.stop();
  if (failures) state.SkipWithError("requests failed");
  state.SetItemsProcessed(state.iterations() * clients * kRequestsPerClient);
}
BENCHMARK(BM_Server)->Args({3, 1})->Args({3, 8})->Args({16, 1})->Args({16, 8})->UseRealTime()->Unit(
    benchmark::kMillisecond);

// The baseline: the classic single-threaded libmodbus server loop (as in libmodbus'
// tests/bandwidth-server-many-up.c pattern): select() over the listener and the clients,
// modbus_receive() + modbus_reply() per readable socket.
class SelectServer {
 public:
  SelectServer() {
    ctx_ = modbus_new_tcp("127.0.0.1", 0);
    mapping_ = modbus_mapping_new(0, 0, 500, 500);
    listener_ = modbus_tcp_listen(ctx_, 32);
    sockaddr_in a{};
    socklen_t len = sizeof a;
    ::getsockname(listener_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    thread_ = std::thread([this] { loop(); });
  }
  ~SelectServer() {
    stop_ = true;
    thread_.join();
    ::close(listener_);
    modbus_mapping_free(mapping_);
    modbus_free(ctx_);
  }
  [[nodiscard]] std::uint16_t port() const { return port_; }

 private:
  void loop() {
    fd_set refset;
    FD_ZERO(&refset);
    FD_SET(listener_, &refset);
    int fdmax = listener_;
    std::uint8_t query[MODBUS_TCP_MAX_ADU_LENGTH];
    while (!stop_) {
      fd_set rdset = refset;
      timeval tv{0, 100000};
      if (::select(fdmax + 1, &rdset, nullptr, nullptr, &tv) <= 0) continue;
      for (int fd = 0; fd <= fdmax; ++fd) {
        if (!FD_ISSET(fd, &rdset)) continue;
        if (fd == listener_) {
          const int c = ::accept(listener_, nullptr, nullptr);
          if (c >= 0 && c < FD_SETSIZE) {
            FD_SET(c, &refset);
            if (c > fdmax) fdmax = c;
          }
          continue;
        }
        modbus_set_socket(ctx_, fd);
        const int rc = modbus_receive(ctx_, query);
        if (rc > 0) {
          modbus_reply(ctx_, query, rc, mapping_);
        } else if (rc == -1) {
          ::close(fd);
          FD_CLR(fd, &refset);
        }
      }
    }
    for (int fd = 0; fd <= fdmax; ++fd)
      if (fd != listener_ && FD_ISSET(fd, &refset)) ::close(fd);
  }
  modbus_t* ctx_ = nullptr;
  modbus_mapping_t* mapping_ = nullptr;
  int listener_ = -1;
  std::uint16_t port_ = 0;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

void BM_LibmodbusSelectServer(benchmark::State& state) {
  const int fc = static_cast<int>(state.range(0));
  const int clients = static_cast<int>(state.range(1));
  SelectServer server;
  int failures = 0;
  for (auto _ : state) failures += run_clients(server.port(), clients, fc);
  if (failures) state.SkipWithError("requests failed");
  state.SetItemsProcessed(state.iterations() * clients * kRequestsPerClient);
}
BENCHMARK(BM_LibmodbusSelectServer)
    ->Args({3, 1})
    ->Args({3, 8})
    ->Args({16, 1})
    ->Args({16, 8})
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_CycleReadWrite(benchmark::State& state) {
  mocks::ModbusDriveServer server(mocks::DriveDevice(profile()), {});
  if (server.start()) {
    state.SkipWithError("server did not start");
    return;
  }
  SteadyClock clock;
  drives::ModbusDriveConfig c;
  c.profile = profile();
  c.port = server.port();
  c.poll_period = std::chrono::milliseconds(1);
  drives::ModbusDrive drive(c, clock);
  DriveCommand cmd;
  std::int64_t max_age_ns = 0;
  for (auto _ : state) {
    const CycleTime t{clock.now(), std::chrono::milliseconds(1)};
    drive.read(t);
    drive.write(t, cmd);
    benchmark::DoNotOptimize(drive.feedback());
    max_age_ns = std::max<std::int64_t>(max_age_ns, drive.feedback().age.count());
  }
  state.counters["exchanges"] = static_cast<double>(drive.link_stats().exchanges);
  state.counters["max_age_ms"] = static_cast<double>(max_age_ns) / 1e6;
  server.stop();
}
BENCHMARK(BM_CycleReadWrite)->Unit(benchmark::kNanosecond);

void BM_HandleRequest(benchmark::State& state) {
  mocks::DriveDevice device(profile());
  const std::uint8_t req[] = {0x00, 0x01, 0x00, 0x00, 0x00, 0x17, 0x01, 0x17, 0x00, 0x0A, 0x00, 0x06, 0x00, 0x00, 0x00,
                              0x06, 0x0C, 0x00, 0x0F, 0x00, 0x08, 0x00, 0x00, 0x10, 0x00, 0x00, 0x00, 0x00, 0x00};
  std::uint8_t out[modbus::kMaxAduSize];
  modbus::HandlerOptions options;
  for (auto _ : state) {
    auto r = device.handle(req, out, options);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_HandleRequest);

}  // namespace
