// gsplat checkpoints as torch.save writes them: a zip archive holding `<name>/data.pkl` (a pickle of
// the saved object, whose tensors refer to storages by key) and `<name>/data/<key>` (the raw bytes
// of each storage). A zip reader, a pickle machine that knows just enough of torch to rebuild
// tensor descriptions, and a gather that honours sizes, strides and offsets.
#include <algorithm>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <unordered_map>

#include "io/byte_order.hpp"
#include "io/formats_detail.hpp"
#include "vksplat/io/formats.hpp"

namespace vksplat::io {
namespace {

namespace fs = std::filesystem;

// ---------------------------------------------------------------------------------------------
// Zip

struct ZipEntry {
    std::string name;
    uint16_t method = 0;
    uint32_t crc = 0;
    uint64_t compressed_size = 0;
    uint64_t size = 0;
    uint64_t local_offset = 0;
};

class ZipArchive {
public:
    ZipArchive(const fs::path& path, std::string where) : where_(std::move(where)), in_(path, std::ios::binary) {
        if (!in_) throw InputError(where_, fs::exists(path) ? "cannot be opened" : "no such file");
        file_size_ = fs::file_size(path);
        read_directory();
    }

    const std::vector<ZipEntry>& entries() const { return entries_; }

    const ZipEntry* find(const std::string& name) const {
        for (const auto& entry : entries_)
            if (entry.name == name) return &entry;
        return nullptr;
    }

    std::string read(const ZipEntry& entry) {
        const std::string at = where_ + ": zip entry '" + entry.name + "'";
        const std::string local = bytes_at(entry.local_offset, 30, at + ": local header");
        if (le<uint32_t>(local, 0) != 0x04034b50) throw InputError(at, "bad local header signature (corrupt zip)");
        const uint64_t data_offset = entry.local_offset + 30 + le<uint16_t>(local, 26) + le<uint16_t>(local, 28);
        if (le<uint16_t>(local, 6) & 0x1) throw InputError(at, "is encrypted, which is not supported");
        std::string data;
        if (entry.method == 0) {
            if (entry.compressed_size != entry.size)
                throw InputError(at, "stored entry's sizes disagree (" + std::to_string(entry.compressed_size) +
                                         " vs " + std::to_string(entry.size) + ")");
            data = bytes_at(data_offset, entry.size, at);
        } else if (entry.method == 8) {
            const std::string compressed = bytes_at(data_offset, entry.compressed_size, at);
            detail::Inflater inflater(compressed, detail::Inflater::Wrapping::raw, at);
            if (inflater.read(data, entry.size) != entry.size)
                throw InputError(at, "truncated: inflates to " + std::to_string(data.size()) + " bytes, expected " +
                                         std::to_string(entry.size));
            if (!inflater.at_end()) throw InputError(at, "inflates to more than its stated " + std::to_string(entry.size) + " bytes");
        } else {
            throw InputError(at, "uses compression method " + std::to_string(entry.method) +
                                     " (only stored (0) and deflate (8) are supported)");
        }
        if (detail::crc32_of(data) != entry.crc) throw InputError(at, "CRC mismatch: the data is corrupt");
        return data;
    }

private:
    template <typename T>
    static T le(const std::string& bytes, size_t offset) {
        return detail::load_little_endian<T>(bytes.data() + offset);
    }

    std::string bytes_at(uint64_t offset, uint64_t count, const std::string& at) {
        if (offset > file_size_ || count > file_size_ - offset)
            throw InputError(at, "truncated: needs bytes " + std::to_string(offset) + " to " +
                                     std::to_string(offset + count) + " but the file has " + std::to_string(file_size_));
        std::string bytes(count, '\0');
        in_.clear();
        in_.seekg(static_cast<std::streamoff>(offset));
        if (!in_.read(bytes.data(), static_cast<std::streamsize>(count)))
            throw InputError(at, "reading " + std::to_string(count) + " bytes failed");
        return bytes;
    }

    void read_directory() {
        // The end-of-central-directory record: 22 bytes plus a comment of up to 65535 at the end.
        const uint64_t tail_size = std::min<uint64_t>(file_size_, 22 + 65535);
        if (file_size_ < 22)
            throw InputError(where_, "not a PyTorch checkpoint: too short (" + std::to_string(file_size_) +
                                         " bytes) to be a zip archive");
        const std::string tail = bytes_at(file_size_ - tail_size, tail_size, where_);
        size_t eocd = std::string::npos;
        for (size_t i = tail_size - 22 + 1; i-- > 0;)
            if (le<uint32_t>(tail, i) == 0x06054b50) {
                eocd = i;
                break;
            }
        if (eocd == std::string::npos) {
            const bool legacy = tail_size >= 2 && static_cast<uint8_t>(tail[0]) == 0x80;
            throw InputError(where_, std::string("not a zip archive (no end-of-central-directory record): ") +
                                         (legacy ? "a legacy (pre-1.6) torch.save file is not supported; re-save "
                                                   "it with a recent PyTorch"
                                                 : "wrong magic or truncated"));
        }
        uint64_t entry_count = le<uint16_t>(tail, eocd + 10);
        uint64_t directory_size = le<uint32_t>(tail, eocd + 12);
        uint64_t directory_offset = le<uint32_t>(tail, eocd + 16);
        const uint64_t eocd_offset = file_size_ - tail_size + eocd;
        if ((entry_count == 0xffff || directory_size == 0xffffffff || directory_offset == 0xffffffff) &&
            eocd_offset >= 20) {
            const std::string locator = bytes_at(eocd_offset - 20, 20, where_ + ": zip64 locator");
            if (le<uint32_t>(locator, 0) == 0x07064b50) {
                const std::string record = bytes_at(le<uint64_t>(locator, 8), 56, where_ + ": zip64 directory record");
                if (le<uint32_t>(record, 0) != 0x06064b50)
                    throw InputError(where_, "bad zip64 end-of-central-directory signature (corrupt zip)");
                entry_count = le<uint64_t>(record, 32);
                directory_size = le<uint64_t>(record, 40);
                directory_offset = le<uint64_t>(record, 48);
            }
        }
        if (directory_offset > file_size_ || directory_size > file_size_ - directory_offset)
            throw InputError(where_, "truncated: the zip directory (" + std::to_string(directory_size) + " bytes at " +
                                         std::to_string(directory_offset) + ") lies beyond the end of the file (" +
                                         std::to_string(file_size_) + " bytes)");
        if (entry_count > directory_size / 46)
            throw InputError(where_, "zip directory claims " + std::to_string(entry_count) + " entries but has room for " +
                                         std::to_string(directory_size / 46));
        const std::string directory = bytes_at(directory_offset, directory_size, where_);
        size_t at = 0;
        for (uint64_t e = 0; e < entry_count; ++e) {
            if (directory.size() - at < 46 || le<uint32_t>(directory, at) != 0x02014b50)
                throw InputError(where_, "corrupt zip directory at entry " + std::to_string(e));
            ZipEntry entry;
            entry.method = le<uint16_t>(directory, at + 10);
            entry.crc = le<uint32_t>(directory, at + 16);
            entry.compressed_size = le<uint32_t>(directory, at + 20);
            entry.size = le<uint32_t>(directory, at + 24);
            const size_t name_length = le<uint16_t>(directory, at + 28);
            const size_t extra_length = le<uint16_t>(directory, at + 30);
            const size_t comment_length = le<uint16_t>(directory, at + 32);
            entry.local_offset = le<uint32_t>(directory, at + 42);
            if (directory.size() - at - 46 < name_length + extra_length + comment_length)
                throw InputError(where_, "corrupt zip directory at entry " + std::to_string(e));
            entry.name = directory.substr(at + 46, name_length);
            // Zip64: the sizes and offset that overflowed 32 bits are in extra field 0x0001, in order.
            for (size_t x = at + 46 + name_length; x + 4 <= at + 46 + name_length + extra_length;) {
                const uint16_t id = le<uint16_t>(directory, x);
                const uint16_t length = le<uint16_t>(directory, x + 2);
                if (id == 0x0001) {
                    size_t field = x + 4;
                    const size_t end = x + 4 + length;
                    for (uint64_t* value : {&entry.size, &entry.compressed_size, &entry.local_offset})
                        if (*value == 0xffffffff && field + 8 <= end) {
                            *value = le<uint64_t>(directory, field);
                            field += 8;
                        }
                }
                x += 4 + length;
            }
            entries_.push_back(std::move(entry));
            at += 46 + name_length + extra_length + comment_length;
        }
    }

    std::string where_;
    std::ifstream in_;
    uint64_t file_size_ = 0;
    std::vector<ZipEntry> entries_;
};

// ---------------------------------------------------------------------------------------------
// Pickle

struct Value;
using Ref = std::shared_ptr<Value>;

struct Value {
    enum class Kind { none, boolean, integer, real, text, bytes, tuple, list, dict, global, storage, tensor, object };
    Kind kind = Kind::none;
    int64_t integer = 0;
    double real = 0;
    std::string text;  // text, bytes, global "module.name", object's type, storage's type
    std::vector<Ref> items;                      // tuple, list
    std::vector<std::pair<Ref, Ref>> entries;    // dict
    // storage
    std::string key;
    int64_t numel = 0;
    // tensor
    Ref storage;
    int64_t offset = 0;
    std::vector<int64_t> sizes, strides;
};

Ref make(Value::Kind kind) {
    auto value = std::make_shared<Value>();
    value->kind = kind;
    return value;
}

Ref make_integer(int64_t v) {
    auto value = make(Value::Kind::integer);
    value->integer = v;
    return value;
}

Ref make_text(Value::Kind kind, std::string text) {
    auto value = make(kind);
    value->text = std::move(text);
    return value;
}

Ref dict_get(const Value& dict, const std::string& key) {
    for (const auto& [k, v] : dict.entries)
        if (k->kind == Value::Kind::text && k->text == key) return v;
    return nullptr;
}

class Unpickler {
public:
    Unpickler(std::string_view bytes, std::string where) : bytes_(bytes), where_(std::move(where)) {}

    Ref run() {
        while (true) {
            const size_t opcode_at = position_;
            const auto opcode = static_cast<uint8_t>(take(1)[0]);
            switch (opcode) {
                case 0x80:  // PROTO
                    take(1);
                    break;
                case 0x95:  // FRAME
                    take(8);
                    break;
                case '.':  // STOP
                    if (stack_.empty()) fail(opcode_at, "STOP with an empty stack");
                    return stack_.back();
                case '(':  // MARK
                    marks_.push_back(stack_.size());
                    break;
                case '0':  // POP
                    pop(opcode_at);
                    break;
                case '1':  // POP_MARK
                    since_mark(opcode_at);
                    break;
                case '2':  // DUP
                    push(top(opcode_at));
                    break;
                case 'N':
                    push(make(Value::Kind::none));
                    break;
                case 0x88:  // NEWTRUE
                case 0x89: {  // NEWFALSE
                    auto value = make(Value::Kind::boolean);
                    value->integer = opcode == 0x88;
                    push(value);
                    break;
                }
                case 'J':  // BININT
                    push(make_integer(detail::load_little_endian<int32_t>(take(4))));
                    break;
                case 'K':  // BININT1
                    push(make_integer(static_cast<uint8_t>(take(1)[0])));
                    break;
                case 'M':  // BININT2
                    push(make_integer(detail::load_little_endian<uint16_t>(take(2))));
                    break;
                case 0x8a:  // LONG1
                    push(make_integer(long_of(static_cast<uint8_t>(take(1)[0]), opcode_at)));
                    break;
                case 0x8b:  // LONG4
                    push(make_integer(long_of(length(4, opcode_at), opcode_at)));
                    break;
                case 'G': {  // BINFLOAT: big-endian double
                    auto value = make(Value::Kind::real);
                    value->real = detail::load_scalar<double>(take(8), detail::kHostIsLittleEndian);
                    push(value);
                    break;
                }
                case 'X':  // BINUNICODE
                    push(make_text(Value::Kind::text, chars(4, opcode_at)));
                    break;
                case 0x8c:  // SHORT_BINUNICODE
                    push(make_text(Value::Kind::text, chars(1, opcode_at)));
                    break;
                case 0x8d:  // BINUNICODE8
                    push(make_text(Value::Kind::text, chars(8, opcode_at)));
                    break;
                case 'T':  // BINSTRING
                case 'B':  // BINBYTES
                    push(make_text(opcode == 'T' ? Value::Kind::text : Value::Kind::bytes,
                                   chars(4, opcode_at)));
                    break;
                case 'U':  // SHORT_BINSTRING
                case 'C':  // SHORT_BINBYTES
                    push(make_text(opcode == 'U' ? Value::Kind::text : Value::Kind::bytes,
                                   chars(1, opcode_at)));
                    break;
                case 0x8e:  // BINBYTES8
                    push(make_text(Value::Kind::bytes, chars(8, opcode_at)));
                    break;
                case '}':  // EMPTY_DICT
                    push(make(Value::Kind::dict));
                    break;
                case ']':  // EMPTY_LIST
                    push(make(Value::Kind::list));
                    break;
                case ')':  // EMPTY_TUPLE
                    push(make(Value::Kind::tuple));
                    break;
                case 0x8f:  // EMPTY_SET
                    push(make_text(Value::Kind::object, "builtins.set"));
                    break;
                case 't': {  // TUPLE
                    auto value = make(Value::Kind::tuple);
                    value->items = since_mark(opcode_at);
                    push(value);
                    break;
                }
                case 0x85:  // TUPLE1
                case 0x86:  // TUPLE2
                case 0x87: {  // TUPLE3
                    const size_t n = opcode - 0x84u;
                    if (stack_.size() < n + floor()) fail(opcode_at, "TUPLE" + std::to_string(n) + " on a short stack");
                    auto value = make(Value::Kind::tuple);
                    value->items.assign(stack_.end() - static_cast<std::ptrdiff_t>(n), stack_.end());
                    stack_.resize(stack_.size() - n);
                    push(value);
                    break;
                }
                case 'l': {  // LIST
                    auto value = make(Value::Kind::list);
                    value->items = since_mark(opcode_at);
                    push(value);
                    break;
                }
                case 'd': {  // DICT
                    auto value = make(Value::Kind::dict);
                    add_pairs(*value, since_mark(opcode_at), opcode_at);
                    push(value);
                    break;
                }
                case 'a': {  // APPEND
                    Ref item = pop(opcode_at);
                    Ref list = top(opcode_at);
                    if (list->kind == Value::Kind::list) list->items.push_back(item);
                    break;
                }
                case 'e': {  // APPENDS
                    auto items = since_mark(opcode_at);
                    Ref list = top(opcode_at);
                    if (list->kind == Value::Kind::list) list->items.insert(list->items.end(), items.begin(), items.end());
                    break;
                }
                case 0x90:  // ADDITEMS
                    since_mark(opcode_at);
                    break;
                case 0x91:  // FROZENSET
                    since_mark(opcode_at);
                    push(make_text(Value::Kind::object, "builtins.frozenset"));
                    break;
                case 's': {  // SETITEM
                    Ref value = pop(opcode_at);
                    Ref key = pop(opcode_at);
                    Ref dict = top(opcode_at);
                    if (dict->kind == Value::Kind::dict) add_pairs(*dict, {key, value}, opcode_at);
                    break;
                }
                case 'u': {  // SETITEMS
                    auto items = since_mark(opcode_at);
                    Ref dict = top(opcode_at);
                    if (dict->kind == Value::Kind::dict) add_pairs(*dict, items, opcode_at);
                    break;
                }
                case 'c': {  // GLOBAL: "module\nname\n"
                    const std::string module = line(opcode_at);
                    const std::string name = line(opcode_at);
                    push(make_text(Value::Kind::global, module + "." + name));
                    break;
                }
                case 0x93: {  // STACK_GLOBAL
                    Ref name = pop(opcode_at);
                    Ref module = pop(opcode_at);
                    if (name->kind != Value::Kind::text || module->kind != Value::Kind::text)
                        fail(opcode_at, "STACK_GLOBAL needs two strings");
                    push(make_text(Value::Kind::global, module->text + "." + name->text));
                    break;
                }
                case 'R': {  // REDUCE
                    Ref args = pop(opcode_at);
                    Ref callable = pop(opcode_at);
                    push(reduce(*callable, *args, opcode_at));
                    break;
                }
                case 0x81: {  // NEWOBJ
                    pop(opcode_at);
                    Ref cls = pop(opcode_at);
                    push(instance_of(*cls));
                    break;
                }
                case 0x92: {  // NEWOBJ_EX
                    pop(opcode_at);
                    pop(opcode_at);
                    Ref cls = pop(opcode_at);
                    push(instance_of(*cls));
                    break;
                }
                case 'b':  // BUILD: sets an object's state; nothing here needs it
                    pop(opcode_at);
                    top(opcode_at);
                    break;
                case 'Q': {  // BINPERSID
                    Ref id = pop(opcode_at);
                    push(storage_of(*id, opcode_at));
                    break;
                }
                case 'q':  // BINPUT
                    memo_put(static_cast<uint8_t>(take(1)[0]), opcode_at);
                    break;
                case 'r':  // LONG_BINPUT
                    memo_put(detail::load_little_endian<uint32_t>(take(4)), opcode_at);
                    break;
                case 0x94:  // MEMOIZE
                    memo_put(memo_.size(), opcode_at);
                    break;
                case 'h':  // BINGET
                    push(memo_get(static_cast<uint8_t>(take(1)[0]), opcode_at));
                    break;
                case 'j':  // LONG_BINGET
                    push(memo_get(detail::load_little_endian<uint32_t>(take(4)), opcode_at));
                    break;
                default: {
                    char text[8];
                    std::snprintf(text, sizeof text, "0x%02x", opcode);
                    fail(opcode_at, std::string("unsupported opcode ") + text +
                                        " (torch.save's pickles use protocol 2 or later)");
                }
            }
        }
    }

private:
    [[noreturn]] void fail(size_t at, const std::string& problem) const {
        throw InputError(where_, "pickle byte " + std::to_string(at) + ": " + problem);
    }

    const char* take(uint64_t count) {
        if (count > bytes_.size() - position_)
            throw InputError(where_, "truncated pickle: needs " + std::to_string(count) + " bytes at byte " +
                                         std::to_string(position_) + " but it has " + std::to_string(bytes_.size()));
        const char* at = bytes_.data() + position_;
        position_ += count;
        return at;
    }

    uint64_t length(int width, size_t at) {
        uint64_t n = 0;
        if (width == 1) n = static_cast<uint8_t>(take(1)[0]);
        else if (width == 4) n = detail::load_little_endian<uint32_t>(take(4));
        else n = detail::load_little_endian<uint64_t>(take(8));
        if (n > bytes_.size() - position_)
            fail(at, "length " + std::to_string(n) + " runs past the end of the pickle (truncated)");
        return n;
    }

    // A length of `width` bytes, then that many bytes.
    std::string chars(int width, size_t at) {
        const uint64_t n = length(width, at);
        return std::string(take(n), n);
    }

    int64_t long_of(uint64_t n, size_t at) {
        if (n > 8) fail(at, "integer of " + std::to_string(n) + " bytes is too large");
        const char* bytes = take(n);
        uint64_t value = 0;
        for (uint64_t i = 0; i < n; ++i) value |= uint64_t{static_cast<uint8_t>(bytes[i])} << (8 * i);
        if (n > 0 && n < 8 && (static_cast<uint8_t>(bytes[n - 1]) & 0x80)) value |= ~uint64_t{0} << (8 * n);
        return static_cast<int64_t>(value);
    }

    std::string line(size_t at) {
        const size_t end = bytes_.find('\n', position_);
        if (end == std::string_view::npos) fail(at, "GLOBAL without a newline (truncated)");
        std::string text(bytes_.substr(position_, end - position_));
        position_ = end + 1;
        return text;
    }

    size_t floor() const { return marks_.empty() ? 0 : marks_.back(); }
    void push(Ref value) { stack_.push_back(std::move(value)); }
    Ref pop(size_t at) {
        if (stack_.size() <= floor()) fail(at, "pop from an empty stack");
        Ref value = std::move(stack_.back());
        stack_.pop_back();
        return value;
    }
    Ref top(size_t at) const {
        if (stack_.size() <= floor()) fail(at, "empty stack");
        return stack_.back();
    }
    std::vector<Ref> since_mark(size_t at) {
        if (marks_.empty()) fail(at, "no MARK");
        const size_t mark = marks_.back();
        marks_.pop_back();
        std::vector<Ref> items(stack_.begin() + static_cast<std::ptrdiff_t>(mark), stack_.end());
        stack_.resize(mark);
        return items;
    }
    void add_pairs(Value& dict, const std::vector<Ref>& items, size_t at) {
        if (items.size() % 2) fail(at, "odd number of items for a dict");
        for (size_t i = 0; i < items.size(); i += 2) dict.entries.emplace_back(items[i], items[i + 1]);
    }
    void memo_put(uint64_t index, size_t at) { memo_[index] = top(at); }
    Ref memo_get(uint64_t index, size_t at) const {
        const auto found = memo_.find(index);
        if (found == memo_.end()) fail(at, "memo entry " + std::to_string(index) + " was never set");
        return found->second;
    }

    static Ref instance_of(const Value& cls) {
        if (cls.kind == Value::Kind::global &&
            (cls.text == "collections.OrderedDict" || cls.text == "builtins.dict" || cls.text == "__builtin__.dict"))
            return make(Value::Kind::dict);
        return make_text(Value::Kind::object, cls.kind == Value::Kind::global ? cls.text : "?");
    }

    static std::vector<int64_t> integers_of(const Value& tuple, const std::string& what, const std::string& where,
                                            size_t at) {
        std::vector<int64_t> values;
        if (tuple.kind != Value::Kind::tuple)
            throw InputError(where, "pickle byte " + std::to_string(at) + ": tensor " + what + " is not a tuple");
        for (const auto& item : tuple.items) {
            if (item->kind != Value::Kind::integer || item->integer < 0)
                throw InputError(where, "pickle byte " + std::to_string(at) + ": tensor " + what +
                                            " holds something other than a non-negative integer");
            values.push_back(item->integer);
        }
        return values;
    }

    Ref reduce(const Value& callable, const Value& args, size_t at) {
        const std::string name = callable.kind == Value::Kind::global ? callable.text : "?";
        if (name == "torch._utils._rebuild_tensor_v2" || name == "torch._utils._rebuild_tensor") {
            // (storage, storage_offset, size, stride, requires_grad, backward_hooks[, metadata])
            if (args.kind != Value::Kind::tuple || args.items.size() < 4 ||
                args.items[0]->kind != Value::Kind::storage || args.items[1]->kind != Value::Kind::integer)
                fail(at, name + " with unexpected arguments");
            auto tensor = make(Value::Kind::tensor);
            tensor->storage = args.items[0];
            tensor->offset = args.items[1]->integer;
            tensor->sizes = integers_of(*args.items[2], "size", where_, at);
            tensor->strides = integers_of(*args.items[3], "stride", where_, at);
            if (tensor->offset < 0 || tensor->sizes.size() != tensor->strides.size())
                fail(at, "tensor with a negative offset or sizes and strides of different lengths");
            return tensor;
        }
        if (name == "torch._utils._rebuild_parameter" || name == "torch._utils._rebuild_parameter_with_state") {
            if (args.kind != Value::Kind::tuple || args.items.empty()) fail(at, name + " without arguments");
            return args.items[0];
        }
        if (name == "collections.OrderedDict" || name == "builtins.dict" || name == "__builtin__.dict" ||
            name == "collections.defaultdict") {
            auto dict = make(Value::Kind::dict);
            // OrderedDict([(key, value), ...]) carries its items in the argument.
            if (args.kind == Value::Kind::tuple && !args.items.empty() && args.items[0]->kind == Value::Kind::list)
                for (const auto& pair : args.items[0]->items)
                    if (pair->kind == Value::Kind::tuple && pair->items.size() == 2)
                        dict->entries.emplace_back(pair->items[0], pair->items[1]);
            return dict;
        }
        // Anything else (numpy scalars, optimizer classes, ...) is kept as an opaque object: it
        // only matters if the splats are in it.
        return make_text(Value::Kind::object, name);
    }

    Ref storage_of(const Value& id, size_t at) {
        // ('storage', storage_type, key, location, numel)
        if (id.kind != Value::Kind::tuple || id.items.size() < 5 || id.items[0]->kind != Value::Kind::text ||
            id.items[0]->text != "storage" || id.items[1]->kind != Value::Kind::global ||
            id.items[2]->kind != Value::Kind::text || id.items[4]->kind != Value::Kind::integer ||
            id.items[4]->integer < 0)
            fail(at, "persistent id is not ('storage', type, key, location, numel)");
        auto storage = make(Value::Kind::storage);
        storage->text = id.items[1]->text;
        storage->key = id.items[2]->text;
        storage->numel = id.items[4]->integer;
        return storage;
    }

    std::string_view bytes_;
    std::string where_;
    size_t position_ = 0;
    std::vector<Ref> stack_;
    std::vector<size_t> marks_;
    // Keyed by index, not a vector grown to the largest: BINPUT may name any index up to 2^32 - 1,
    // and 5 bytes must not cost gigabytes.
    std::unordered_map<uint64_t, Ref> memo_;
};

// ---------------------------------------------------------------------------------------------
// Tensors

float half_to_float(uint16_t h) {
    const uint32_t sign = uint32_t{h & 0x8000u} << 16;
    const uint32_t exponent = (h >> 10) & 0x1f;
    uint32_t mantissa = h & 0x3ffu;
    uint32_t bits = 0;
    if (exponent == 0) {
        if (mantissa == 0) {
            bits = sign;
        } else {  // subnormal: normalise
            int e = -1;
            do {
                ++e;
                mantissa <<= 1;
            } while (!(mantissa & 0x400u));
            bits = sign | ((127 - 15 - e) << 23) | ((mantissa & 0x3ffu) << 13);
        }
    } else if (exponent == 31) {
        bits = sign | 0x7f800000u | (mantissa << 13);
    } else {
        bits = sign | ((exponent + 127 - 15) << 23) | (mantissa << 13);
    }
    float value;
    std::memcpy(&value, &bits, 4);
    return value;
}

struct DType {
    const char* storage;
    const char* name;
    size_t bytes;
};
constexpr DType kFloatTypes[] = {{"torch.FloatStorage", "float32", 4},
                                 {"torch.HalfStorage", "float16", 2},
                                 {"torch.BFloat16Storage", "bfloat16", 2},
                                 {"torch.DoubleStorage", "float64", 8}};

class TensorReader {
public:
    TensorReader(ZipArchive& zip, std::string prefix, bool swap, std::string where)
        : zip_(zip), prefix_(std::move(prefix)), swap_(swap), where_(std::move(where)) {}

    // The tensor's values in row-major order of its sizes, as float.
    std::vector<float> gather(const Value& tensor, const std::string& name) {
        const std::string at = where_ + ": tensor '" + name + "'";
        const Value& storage = *tensor.storage;
        const DType* dtype = nullptr;
        for (const auto& type : kFloatTypes)
            if (storage.text == type.storage) dtype = &type;
        if (!dtype) throw InputError(at, "has storage type " + storage.text + "; expected a floating-point tensor");

        // Elements the view reaches: offset + sum((size - 1) * stride) must lie within the storage.
        uint64_t count = 1;
        uint64_t last = static_cast<uint64_t>(tensor.offset);
        bool overflow = false;
        for (size_t d = 0; d < tensor.sizes.size(); ++d) {
            const auto size = static_cast<uint64_t>(tensor.sizes[d]);
            if (__builtin_mul_overflow(count, size, &count)) throw InputError(at, "element count overflows");
            uint64_t reach = 0;
            if (size > 0 && (__builtin_mul_overflow(size - 1, static_cast<uint64_t>(tensor.strides[d]), &reach) ||
                             __builtin_add_overflow(last, reach, &last)))
                overflow = true;
        }
        if (count > 0 && (overflow || last >= static_cast<uint64_t>(storage.numel)))
            throw InputError(at, "reaches " + (overflow ? std::string("beyond 2^64 elements") : "element " + std::to_string(last)) +
                                     " of storage '" + storage.key + "', which has only " +
                                     std::to_string(storage.numel) + " (sizes, strides or offset are corrupt)");
        // A view that repeats elements (a zero stride) may hold more than its storage; a parameter
        // never does, and allowing it would let a few bytes describe 2^40 Gaussians.
        if (count > static_cast<uint64_t>(storage.numel))
            throw InputError(at, "has " + std::to_string(count) + " elements but its storage '" + storage.key +
                                     "' only " + std::to_string(storage.numel) +
                                     " (a broadcast view, or corrupt sizes and strides)");

        const std::string& bytes = storage_bytes(storage, *dtype, at);
        std::vector<float> values(count);
        std::vector<uint64_t> index(tensor.sizes.size(), 0);
        for (uint64_t i = 0; i < count; ++i) {
            uint64_t element = static_cast<uint64_t>(tensor.offset);
            for (size_t d = 0; d < index.size(); ++d) element += index[d] * static_cast<uint64_t>(tensor.strides[d]);
            values[i] = load(bytes.data() + element * dtype->bytes, *dtype);
            for (size_t d = index.size(); d-- > 0;) {
                if (++index[d] < static_cast<uint64_t>(tensor.sizes[d])) break;
                index[d] = 0;
            }
        }
        return values;
    }

private:
    float load(const char* bytes, const DType& dtype) const {
        switch (dtype.bytes) {
            case 4:
                return detail::load_scalar<float>(bytes, swap_);
            case 8:
                return static_cast<float>(detail::load_scalar<double>(bytes, swap_));
            default: {
                const auto bits = detail::load_scalar<uint16_t>(bytes, swap_);
                if (dtype.storage == std::string_view("torch.HalfStorage")) return half_to_float(bits);
                const uint32_t wide = uint32_t{bits} << 16;
                float value;
                std::memcpy(&value, &wide, 4);
                return value;
            }
        }
    }

    const std::string& storage_bytes(const Value& storage, const DType& dtype, const std::string& at) {
        if (const auto found = cache_.find(storage.key); found != cache_.end()) return found->second;
        const std::string entry_name = prefix_ + "data/" + storage.key;
        const ZipEntry* entry = zip_.find(entry_name);
        if (!entry) throw InputError(at, "its storage '" + entry_name + "' is missing from the archive");
        uint64_t needed = 0;
        if (__builtin_mul_overflow(static_cast<uint64_t>(storage.numel), dtype.bytes, &needed) || entry->size < needed)
            throw InputError(at, "storage '" + entry_name + "' holds " + std::to_string(entry->size) + " bytes but " +
                                     std::to_string(storage.numel) + " " + dtype.name + " elements need " +
                                     std::to_string(needed) + " (truncated?)");
        return cache_.emplace(storage.key, zip_.read(*entry)).first->second;
    }

    ZipArchive& zip_;
    std::string prefix_;
    bool swap_;
    std::string where_;
    std::map<std::string, std::string> cache_;
};

std::string shape_text(const std::vector<int64_t>& sizes) {
    std::string text = "[";
    for (size_t d = 0; d < sizes.size(); ++d) text += (d ? ", " : "") + std::to_string(sizes[d]);
    return text + "]";
}

}  // namespace

GaussianCloud read_gsplat_checkpoint(const fs::path& path, std::vector<std::string>* notes) {
    const std::string where = path.string();
    ZipArchive zip(path, where);

    // torch.save names every entry "<archive name>/...": find the pickle to learn the prefix.
    const ZipEntry* pickle_entry = nullptr;
    for (const auto& entry : zip.entries()) {
        const std::string& name = entry.name;
        const bool is_pickle = name == "data.pkl" || (name.size() > 9 && name.compare(name.size() - 9, 9, "/data.pkl") == 0);
        if (is_pickle && (!pickle_entry || name.size() < pickle_entry->name.size())) pickle_entry = &entry;
    }
    if (!pickle_entry) throw InputError(where, "not a PyTorch checkpoint: the zip archive has no data.pkl");
    const std::string prefix = pickle_entry->name.substr(0, pickle_entry->name.size() - 8);
    bool swap = !detail::kHostIsLittleEndian;
    if (const ZipEntry* order = zip.find(prefix + "byteorder")) {
        const std::string text = zip.read(*order);
        if (text != "little" && text != "big") throw InputError(where, "unknown byte order '" + text + "'");
        swap = (text == "big") == detail::kHostIsLittleEndian;
    }

    const std::string pickle = zip.read(*pickle_entry);
    const Ref root = Unpickler(pickle, where + ": " + pickle_entry->name).run();
    if (root->kind != Value::Kind::dict) throw InputError(where, "the checkpoint is not a dictionary");
    Ref splats = dict_get(*root, "splats");
    if (!splats && dict_get(*root, "means")) splats = root;
    if (!splats || splats->kind != Value::Kind::dict) {
        std::string keys;
        for (const auto& [key, value] : root->entries)
            if (key->kind == Value::Kind::text) keys += (keys.empty() ? "" : ", ") + key->text;
        throw InputError(where, "has no 'splats' dictionary of tensors (top-level keys: " +
                                    (keys.empty() ? std::string("none") : keys) + ")");
    }

    const auto tensor = [&](const std::string& name, bool required) -> Ref {
        const Ref value = dict_get(*splats, name);
        if (!value) {
            if (required) throw InputError(where, "splats has no '" + name + "' tensor");
            return nullptr;
        }
        if (value->kind != Value::Kind::tensor)
            throw InputError(where, "splats['" + name + "'] is not a tensor");
        return value;
    };
    const Ref means = tensor("means", true);
    const Ref quats = tensor("quats", true);
    const Ref scales = tensor("scales", true);
    const Ref opacities = tensor("opacities", true);
    const Ref sh0 = tensor("sh0", true);
    const Ref sh_rest = tensor("shN", false);

    if (means->sizes.size() != 2 || means->sizes[1] != 3)
        throw InputError(where, "tensor 'means' has shape " + shape_text(means->sizes) + "; expected [N, 3]");
    const int64_t n = means->sizes[0];
    const auto expect_shape = [&](const Ref& t, const std::string& name, std::vector<std::vector<int64_t>> shapes,
                                  const std::string& expected) {
        for (const auto& shape : shapes)
            if (t->sizes == shape) return;
        throw InputError(where, "tensor '" + name + "' has shape " + shape_text(t->sizes) + "; expected " + expected +
                                    " with N = " + std::to_string(n) + " (from 'means')");
    };
    expect_shape(quats, "quats", {{n, 4}}, "[N, 4]");
    expect_shape(scales, "scales", {{n, 3}}, "[N, 3]");
    expect_shape(opacities, "opacities", {{n}, {n, 1}}, "[N]");
    expect_shape(sh0, "sh0", {{n, 1, 3}, {n, 3}}, "[N, 1, 3]");
    int sh_degree = 0;
    if (sh_rest) {
        const int64_t k = sh_rest->sizes.size() == 3 ? sh_rest->sizes[1] : -1;
        for (int degree = 0; degree <= 3; ++degree)
            if (k == sh_coefficients_for_degree(degree) - 1) sh_degree = degree;
        if (sh_rest->sizes.size() != 3 || sh_rest->sizes[0] != n || sh_rest->sizes[2] != 3 ||
            k != sh_coefficients_for_degree(sh_degree) - 1)
            throw InputError(where, "tensor 'shN' has shape " + shape_text(sh_rest->sizes) +
                                        "; expected [N, K, 3] with K = 0, 3, 8 or 15 and N = " + std::to_string(n));
    }

    // Gathered before the cloud is sized for n: gather checks each tensor against the bytes really in
    // the archive, so n is then known to be backed by data.
    TensorReader reader(zip, prefix, swap, where);
    std::vector<float> positions = reader.gather(*means, "means");
    std::vector<float> rotations = reader.gather(*quats, "quats");  // gsplat's quaternions are w, x, y, z too
    std::vector<float> log_scales = reader.gather(*scales, "scales");
    std::vector<float> opacity_logits = reader.gather(*opacities, "opacities");
    const std::vector<float> dc = reader.gather(*sh0, "sh0");
    const std::vector<float> rest = sh_rest ? reader.gather(*sh_rest, "shN") : std::vector<float>{};
    GaussianCloud cloud;
    cloud.sh_degree = sh_degree;
    cloud.resize(static_cast<size_t>(n));
    cloud.positions = std::move(positions);
    cloud.rotations = std::move(rotations);
    cloud.log_scales = std::move(log_scales);
    cloud.opacity_logits = std::move(opacity_logits);
    // Both are [coefficient][rgb] per Gaussian, as the cloud is: DC first, then the rest.
    const size_t coefficients = static_cast<size_t>(cloud.sh_coefficients());
    for (size_t i = 0; i < static_cast<size_t>(n); ++i) {
        std::copy_n(dc.begin() + static_cast<std::ptrdiff_t>(i * 3), 3, cloud.sh.begin() + static_cast<std::ptrdiff_t>(i * coefficients * 3));
        std::copy_n(rest.begin() + static_cast<std::ptrdiff_t>(i * (coefficients - 1) * 3), (coefficients - 1) * 3,
                    cloud.sh.begin() + static_cast<std::ptrdiff_t>(i * coefficients * 3 + 3));
    }

    if (notes) {
        std::string ignored;
        for (const auto& [key, value] : splats->entries) {
            if (key->kind != Value::Kind::text) continue;
            static const std::set<std::string> used = {"means", "quats", "scales", "opacities", "sh0", "shN"};
            if (!used.count(key->text)) ignored += (ignored.empty() ? "" : ", ") + key->text;
        }
        if (!ignored.empty())
            notes->push_back(where + ": ignored splats entries " + ignored + " (a Gaussian cloud has no place for them)");
        if (const Ref step = dict_get(*root, "step"); step && step != splats && step->kind == Value::Kind::integer)
            notes->push_back(where + ": checkpoint of step " + std::to_string(step->integer));
    }
    return cloud;
}

}  // namespace vksplat::io
