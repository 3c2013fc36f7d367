//! The grader's general hints: what a panic, an endless loop, a dead program or a candle
//! error usually means, whatever the exercise, in the current language. Hints about an
//! exercise's own mistakes live beside its lesson, in `lessons/NN-slug/exercise.toml`
//! ([`super::prose`]).

use crate::i18n::t;

/// The hint for a function that never returned.
#[must_use]
pub fn timed_out() -> &'static str {
    t(
        "Check that every loop ends: a loop whose counter never moves, or \
         a `while` whose condition stays true, never returns.",
        "检查每个循环都会结束：计数器从不变化的循环，或条件一直为真的 `while`，都永远不会返回。",
    )
}

/// The hint for a program that died.
#[must_use]
pub fn crashed() -> &'static str {
    t(
        "The program died on this input: unbounded recursion (stack \
         overflow) or std::process::exit are the usual causes.",
        "程序在这个输入上崩溃了：常见原因是无限递归（栈溢出）或调用了 std::process::exit。",
    )
}

/// The hint for a function that is still the starter's `todo!()`.
#[must_use]
pub fn not_started() -> &'static str {
    t(
        "The starter's todo!() is still there: replace it with your implementation.",
        "初始代码里的 todo!() 还在：把它换成你的实现。",
    )
}

/// The hint for a panic with `message`.
#[must_use]
pub fn panic(message: &str) -> String {
    let hint = if message.contains("not yet implemented") {
        not_started()
    } else if message.contains("out of bounds") || message.contains("range end index") {
        t(
            "An index went past the end of a slice: check the loop bounds (a single step, or the \
             first and last positions, are the usual suspects).",
            "某个下标越过了切片的末尾：检查循环的边界（只有一步的输入，或第一个、最后一个位置，最容易出错）。",
        )
    } else if message.contains("overflow") {
        t(
            "An integer went out of range, often a usize going below 0 (like i - 1 at i = 0): \
             check the bounds of your loops.",
            "某个整数超出了范围，常见的是 usize 减到 0 以下（例如 i = 0 时的 i - 1）：检查循环的边界。",
        )
    } else {
        t(
            "Your function panicked on this input: run it by hand on the input above.",
            "你的函数在这个输入上发生了异常（panic）：用上面的输入手算一遍。",
        )
    };
    hint.to_string()
}

/// The hint for an error a candle function returned.
#[must_use]
pub fn error(message: &str) -> String {
    let hint = if message.contains("not a scalar") {
        t(
            "Each loss must be a single number: mean_all() averages every element into a scalar \
             (mean(0) leaves a shape [1]).",
            "每个损失都必须是一个数：mean_all() 把所有元素平均成一个标量（mean(0) 会留下形状 [1]）。",
        )
    } else if message.contains("shape mismatch") || message.contains("broadcast") {
        t(
            "The shapes do not line up: probs is (N, 2) and every other column (N, 1); \
             probs.gather(actions, 1) picks the action's probability as (N, 1), and the \
             operators +, -, * need equal shapes (or the broadcast_ versions).",
            "形状对不上：probs 是 (N, 2)，其他各列都是 (N, 1)；probs.gather(actions, 1) 取出所选动作的概率，\
             形状为 (N, 1)；运算符 +、-、* 要求形状相同（否则用 broadcast_ 版本）。",
        )
    } else if message.contains("dtype") {
        t(
            "Mixed dtypes: the tensors are f32 and candle does not convert implicitly; scalars \
             like 1.0 - eps go straight into clamp or affine, and Tensor::new(&[1.0], ..) makes \
             an f64 tensor.",
            "数据类型混用了：这些张量是 f32，而 candle 不会隐式转换；像 1.0 - eps 这样的标量直接传给 clamp 或 affine，\
             而 Tensor::new(&[1.0], ..) 会得到一个 f64 张量。",
        )
    } else {
        t(
            "Your function returned an error on this input: read the message, then run the \
             candle operations on the input above one by one.",
            "你的函数在这个输入上返回了错误：先读错误信息，再用上面的输入逐个运行其中的 candle 运算。",
        )
    };
    hint.to_string()
}
