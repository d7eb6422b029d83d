#pragma once
// Python pickles (protocol 2 and later) as torch.save writes them, read by a stack machine that
// rebuilds plain values (None, booleans, integers, floats, strings, tuples, lists, dicts) and knows
// just enough of torch to describe a tensor (its storage's key and type, offset, sizes, strides)
// without its data. Classes it does not know become opaque objects that keep their name.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vksplat::io::pickle {

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

// The object the pickle's STOP returns. Every error is an InputError naming `where` and the byte
// of the pickle where it was found.
Ref load(std::string_view bytes, std::string where);

// The value of a dict's text key `key`, or null.
Ref dict_get(const Value& dict, const std::string& key);

}  // namespace vksplat::io::pickle
