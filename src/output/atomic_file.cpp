#include "output/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include "output/posix_file.h"

namespace peensim {

void write_file_atomically(const std::string& path, std::string_view content, Durability durability) {
    const std::string tmp = path + ".tmp";
    const int fd = posix_file::open_or_throw(tmp, O_WRONLY | O_CREAT | O_TRUNC);
    try {
        posix_file::write_all(fd, content.data(), content.size(), tmp);
        if (durability == Durability::power_cut) posix_file::fsync_or_throw(fd, tmp);
    } catch (...) {
        ::close(fd);
        ::unlink(tmp.c_str());
        throw;
    }
    try {
        posix_file::close_or_throw(fd, tmp);
        posix_file::rename_or_throw(tmp, path);
    } catch (...) {
        ::unlink(tmp.c_str());
        throw;
    }
    if (durability == Durability::power_cut) posix_file::fsync_directory(posix_file::parent_directory(path));
}

}  // namespace peensim
