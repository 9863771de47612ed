#include "capture/pcap_source.hpp"

#include <fmt/format.h>
#include <pcap/pcap.h>

namespace dpscope {

std::string link_type_name(int link_type) {
    if (link_type == kLinkTypeProfibusDl) return "PROFIBUS_DL";
    if (link_type == kLinkTypeUser0) return "USER0";
    const char* name = pcap_datalink_val_to_name(link_type);
    return name ? name : "unknown";
}

namespace {

class PcapSource final : public TelegramSource {
  public:
    PcapSource(pcap_t* handle, std::string name, bool classic_pcap)
        : TelegramSource(std::move(name)), handle_(handle), classic_pcap_(classic_pcap) {
        link_type_ = pcap_datalink(handle_);
    }
    ~PcapSource() override { pcap_close(handle_); }

    InputFormat format() const override {
        return classic_pcap_ ? InputFormat::Pcap : InputFormat::Pcapng;
    }
    int link_type() const override { return link_type_; }

    bool next(Record& record) override {
        if (finished_) return false;
        pcap_pkthdr* header = nullptr;
        const u_char* data = nullptr;
        int rc = pcap_next_ex(handle_, &header, &data);
        if (rc == 1) {
            ++number_;
            record.bytes = Bytes(data, header->caplen);
            record.time_ns = static_cast<std::int64_t>(header->ts.tv_sec) * 1'000'000'000 +
                             static_cast<std::int64_t>(header->ts.tv_usec);
            record.number = number_;
            record.offset = classic_pcap_ ? offset_ : 0;
            record.original_length = header->len;
            if (header->caplen < header->len)
                report(Severity::Warning,
                       fmt::format("{}: {}: only {} of {} bytes captured (snapshot length)", name(),
                                   where(number_), header->caplen, header->len));
            offset_ += kPcapRecordHeaderBytes + header->caplen;
            return true;
        }
        finished_ = true;
        if (rc == PCAP_ERROR_BREAK) return false;  // end of file
        set_status(InputStatus::Damaged);
        report(Severity::Error,
               fmt::format("{}: {}: {}; decoding stopped after {} record(s)", name(),
                           where(number_ + 1), pcap_geterr(handle_), number_));
        return false;
    }

  private:
    std::string where(std::uint64_t record) const {
        if (classic_pcap_) return fmt::format("record {} (byte offset {})", record, offset_);
        return fmt::format("record {}", record);
    }

    pcap_t* handle_;
    bool classic_pcap_;
    int link_type_ = 0;
    bool finished_ = false;
    std::uint64_t number_ = 0;
    std::uint64_t offset_ = kPcapFileHeaderBytes;
};

}  // namespace

std::unique_ptr<TelegramSource> open_pcap_source(FILE* file, const std::string& name,
                                                 bool classic_pcap, std::string& error) {
    char errbuf[PCAP_ERRBUF_SIZE] = {};
    pcap_t* handle =
        pcap_fopen_offline_with_tstamp_precision(file, PCAP_TSTAMP_PRECISION_NANO, errbuf);
    if (!handle) {
        std::fclose(file);
        error = fmt::format("{}: not a readable pcap or pcapng file: {}", name, errbuf);
        return nullptr;
    }
    int link_type = pcap_datalink(handle);
    if (link_type != kLinkTypeProfibusDl && link_type != kLinkTypeUser0) {
        error = fmt::format(
            "{}: unsupported link type {} ({}); dpscope reads 257 (PROFIBUS_DL) "
            "and 147 (USER0)",
            name, link_type, link_type_name(link_type));
        pcap_close(handle);
        return nullptr;
    }
    return std::make_unique<PcapSource>(handle, name, classic_pcap);
}

}  // namespace dpscope
