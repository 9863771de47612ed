// The baseline: a bare libpcap loop that only reads the records of a capture (no decoding).
#include <pcap/pcap.h>

#include <cstdio>

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: dpscope_pcap_loop FILE\n");
        return 2;
    }
    char errbuf[PCAP_ERRBUF_SIZE];
    pcap_t* handle =
        pcap_open_offline_with_tstamp_precision(argv[1], PCAP_TSTAMP_PRECISION_NANO, errbuf);
    if (!handle) {
        std::fprintf(stderr, "%s\n", errbuf);
        return 2;
    }
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    unsigned long records = 0, bytes = 0;
    while (pcap_next_ex(handle, &header, &data) == 1) {
        ++records;
        bytes += header->caplen;
    }
    pcap_close(handle);
    std::printf("%lu records, %lu bytes\n", records, bytes);
    return 0;
}
