#include "io/pickle.hpp"

#include <cstdio>
#include <unordered_map>

#include "io/byte_order.hpp"
#include "vksplat/error.hpp"

namespace vksplat::io::pickle {
namespace {

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

}  // namespace

Ref load(std::string_view bytes, std::string where) { return Unpickler(bytes, std::move(where)).run(); }

Ref dict_get(const Value& dict, const std::string& key) {
    for (const auto& [k, v] : dict.entries)
        if (k->kind == Value::Kind::text && k->text == key) return v;
    return nullptr;
}

}  // namespace vksplat::io::pickle
