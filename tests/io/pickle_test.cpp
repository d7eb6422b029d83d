// The pickle reader alone, on pickles written by hand (tests/io/torch_save_writer.hpp): plain values
// of every opcode torch.save uses, shared objects through the memo, a tensor's description without
// its data, and malformed pickles refused with the byte where they go wrong.
#include <gtest/gtest.h>

#include "io/io_test_helpers.hpp"
#include "io/pickle.hpp"
#include "io/torch_save_writer.hpp"

namespace vksplat::io::test {
namespace {

using pickle::Value;

TEST(Pickle, PlainValues) {
    Pickle p;
    p.op('}').mark();
    p.text("small").integer(200).text("medium").integer(60000).text("negative").integer(-5);
    p.text("long").op('\x8a').op('\x02');  // LONG1 of two bytes: 0xff80 sign-extended, -128
    p.bytes_ += "\x80\xff";
    p.text("real").op('G');
    p.bytes_ += std::string("\x3f\xf8\0\0\0\0\0\0", 8);  // 1.5, big-endian
    p.text("yes").op('\x88').text("nothing").op('N');
    p.text("pair").integer(1).integer(2).op('\x86');
    p.text("list").op(']').mark().integer(7).integer(8).op('e');
    p.op('u');
    const pickle::Ref root = pickle::load(p.finish(), "plain.pkl");

    ASSERT_EQ(root->kind, Value::Kind::dict);
    EXPECT_EQ(root->entries.size(), 9u);
    EXPECT_EQ(pickle::dict_get(*root, "small")->integer, 200);
    EXPECT_EQ(pickle::dict_get(*root, "medium")->integer, 60000);
    EXPECT_EQ(pickle::dict_get(*root, "negative")->integer, -5);
    EXPECT_EQ(pickle::dict_get(*root, "long")->integer, -128);
    EXPECT_EQ(pickle::dict_get(*root, "real")->real, 1.5);
    EXPECT_EQ(pickle::dict_get(*root, "yes")->kind, Value::Kind::boolean);
    EXPECT_EQ(pickle::dict_get(*root, "yes")->integer, 1);
    EXPECT_EQ(pickle::dict_get(*root, "nothing")->kind, Value::Kind::none);
    const pickle::Ref pair = pickle::dict_get(*root, "pair");
    ASSERT_EQ(pair->kind, Value::Kind::tuple);
    ASSERT_EQ(pair->items.size(), 2u);
    EXPECT_EQ(pair->items[1]->integer, 2);
    const pickle::Ref list = pickle::dict_get(*root, "list");
    ASSERT_EQ(list->kind, Value::Kind::list);
    ASSERT_EQ(list->items.size(), 2u);
    EXPECT_EQ(list->items[0]->integer, 7);
    EXPECT_EQ(pickle::dict_get(*root, "absent"), nullptr);
}

TEST(Pickle, TensorsAreDescribedAndShareTheirStorageThroughTheMemo) {
    Pickle p;
    p.op('}').mark();
    p.text("a").tensor("HalfStorage", "7", 24, 2, {2, 3}, {6, 2}, 1);
    p.text("b").tensor("HalfStorage", "7", 24, 0, {4}, {1}, 1, true);
    p.op('u');
    const pickle::Ref root = pickle::load(p.finish(), "tensors.pkl");

    const pickle::Ref a = pickle::dict_get(*root, "a");
    const pickle::Ref b = pickle::dict_get(*root, "b");
    ASSERT_EQ(a->kind, Value::Kind::tensor);
    ASSERT_EQ(b->kind, Value::Kind::tensor);
    EXPECT_EQ(a->offset, 2);
    EXPECT_EQ(a->sizes, (std::vector<int64_t>{2, 3}));
    EXPECT_EQ(a->strides, (std::vector<int64_t>{6, 2}));
    EXPECT_EQ(a->storage->kind, Value::Kind::storage);
    EXPECT_EQ(a->storage->text, "torch.HalfStorage");
    EXPECT_EQ(a->storage->key, "7");
    EXPECT_EQ(a->storage->numel, 24);
    EXPECT_EQ(a->storage, b->storage);  // one object, fetched from the memo
}

TEST(PickleErrors, MalformedPicklesNameTheByte) {
    Pickle truncated;
    truncated.text("a string whose end is cut off");
    const std::string cut = truncated.finish().substr(0, 12);
    expect_input_error([&] { pickle::load(cut, "cut.pkl"); }, {"cut.pkl", "pickle byte 2", "truncated"});

    Pickle unknown;
    unknown.op('I');  // protocol 0's INT
    expect_input_error([&] { pickle::load(unknown.finish(), "old.pkl"); },
                       {"old.pkl", "pickle byte 2", "unsupported opcode 0x49"});

    Pickle unset;
    unset.get(5);
    expect_input_error([&] { pickle::load(unset.finish(), "memo.pkl"); }, {"memo.pkl", "memo entry 5 was never set"});

    Pickle empty;
    expect_input_error([&] { pickle::load(empty.finish(), "empty.pkl"); }, {"empty.pkl", "STOP with an empty stack"});

    Pickle odd;
    odd.op('}').mark().text("key").op('u');
    expect_input_error([&] { pickle::load(odd.finish(), "odd.pkl"); }, {"odd.pkl", "odd number of items"});
}

}  // namespace
}  // namespace vksplat::io::test
