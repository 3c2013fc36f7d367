//! The command line's help in Chinese: one catalogue keyed by id.
//!
//! The English help stays where clap derive reads it, in the `///` doc comments of
//! `cli.rs` and `cli/*.rs`. The Chinese lives only here, in [`HELP_ZH`], keyed by the
//! command's path and the argument's id, never by the English text. When the language is
//! Chinese, [`localise`] builds `Cli::command()`, walks the whole tree (every subcommand,
//! the hidden `dev` ones, clap's own `help` subcommand and `-h`/`--help`/`-V`/`--version`)
//! and replaces every text clap prints: abouts, argument help, value names, defaults,
//! possible values, the section headings (a help template) and the usage line.
//!
//! Keys:
//! - a command by its path from the top, `.`-separated: `train`, `dev.notebooks`; the
//!   program itself is `ppo-tutor`; clap's `help` subcommand is `*help`;
//! - `PATH#long` its long about, `PATH#after` its text after the options (`#after_long`
//!   for the long help's);
//! - an argument by `PATH:ID` (its clap id, the field's name): `train:episodes`, with
//!   `#long` for its long help; global arguments and clap's own flags by `*:ID` (`*:lang`,
//!   `*:help`, `*:version`; `*:help+` is the help flag of a command that also has a long
//!   help, which says how to see the other one);
//! - a possible value's help by `PATH:ID=VALUE`: `train:objective=clip`.
//!
//! Value names (`<FILE>`, `<SEED>`) are translated by [`VALUE_NAMES_ZH`], keyed by the
//! name the code gives them. A test walks the tree and fails naming each key without a
//! Chinese entry and each entry whose key no longer exists; another renders every help in
//! Chinese and fails on an English word outside code and identifiers.
//!
//! To add or change a help text: write the English doc comment, then its entry here under
//! the key the failing test names. A third language would add its own catalogue beside this
//! one and pick it in [`localise`] by [`Lang`](crate::i18n::Lang).

use clap::Command;
use clap::builder::StyledStr;

/// The Chinese of every help text the command line prints, keyed as the module says.
pub const HELP_ZH: &[(&str, &str)] = &[
    // The program, its global flag and clap's own flags and `help` subcommand.
    (
        "ppo-tutor",
        "边运行边学习近端策略优化（PPO）：一个终端里的教程，带原生的车杆（CartPole-v1）和一个与原教程 PyTorch 代码逐步一致的 candle PPO",
    ),
    (
        "ppo-tutor#after",
        "界面语言：任何命令都可加 `--lang zh` 或 `--lang en`；否则看 PPO_TUTOR_LANG=zh|en；再否则跟随系统语言（LC_ALL、LC_MESSAGES、LANG 以 zh 开头即为中文）。",
    ),
    (
        "*:lang",
        "界面上所有文字的语言：en 或 zh（默认看 PPO_TUTOR_LANG，再看系统语言：LC_ALL、LC_MESSAGES、LANG 以 zh 开头即为中文）",
    ),
    ("*:help", "打印帮助"),
    ("*:help+", "打印帮助（用 --help 查看完整说明）"),
    ("*:help+#long", "打印帮助（用 -h 查看摘要）"),
    ("*:version", "打印版本"),
    ("*help", "打印本帮助，或所给子命令的帮助"),
    // cartpole
    (
        "cartpole",
        "运行原生的车杆环境：用随机种子重置，依次执行动作，打印轨迹",
    ),
    (
        "cartpole#after",
        "示例：\n  ppo-tutor cartpole --seed 0 --actions 0,1,1,0 --json\n  ppo-tutor cartpole --seed 3 --policy lean --render\n  ppo-tutor cartpole --envs 4 --seed 0 --autoreset next-step --actions-file steps.json --json",
    ),
    (
        "cartpole:seed",
        "reset(seed=...) 的随机种子，0 到 2^64-1 之间的任意整数",
    ),
    (
        "cartpole:actions",
        "依次执行的动作，用逗号分隔，0（左）/ 1（右）；'' 表示只重置",
    ),
    ("cartpole:policy", "用一个策略选动作，代替 --actions"),
    ("cartpole:policy=random", "均匀随机的动作（由 --seed 决定）"),
    (
        "cartpole:policy=lean",
        "朝杆倾斜的方向推，另有 10% 的随机动作：回合很长",
    ),
    (
        "cartpole:max_steps",
        "--policy 最多执行的步数（时限也会结束回合）",
    ),
    (
        "cartpole:env_id",
        "Gymnasium 环境 ID：CartPole-v1（时限 500 步）或 CartPole-v0（200 步）",
    ),
    (
        "cartpole:semi_implicit",
        "用半隐式欧拉法，代替 Gymnasium 默认的显式欧拉法",
    ),
    (
        "cartpole:sutton_barto_reward",
        "Gymnasium 的 sutton_barto_reward：每步奖励 0，杆倒下时 -1",
    ),
    (
        "cartpole:resets",
        "再记录 <次数> 次不带随机种子的重置后的状态（记在 `next_resets` 里）",
    ),
    (
        "cartpole:envs",
        "把 <个数> 个车杆一起步进，如同 Gymnasium 的 `SyncVectorEnv`（环境 i 用种子 seed + i 重置）；需要 --actions-file",
    ),
    (
        "cartpole:autoreset",
        "配合 --envs：回合结束的环境如何重置，`same-step`（Gymnasium 0.29、CleanRL）或 `next-step`（Gymnasium 1.x）",
    ),
    (
        "cartpole:autoreset=same-step",
        "结束的那一步就返回下一回合的第一个观测，真正的最后观测放在 final_obs 里",
    ),
    (
        "cartpole:autoreset=next-step",
        "结束的那一步返回真正的最后观测；下一步才重置该环境",
    ),
    (
        "cartpole:actions_file",
        "配合 --envs <个数>：一个 JSON 文件，由步组成的数组，每步是 <个数> 个 0 或 1 的动作，例如 [[0, 1], [1, 1]]",
    ),
    (
        "cartpole:json",
        "打印一个 JSON 对象，格式与 Gymnasium 的参照轨迹文件相同",
    ),
    (
        "cartpole:render",
        "在终端里画出小车和杆的动画，而不是打印表格",
    ),
    // pendulum
    (
        "pendulum",
        "运行原生的倒立摆（Pendulum-v1）：用随机种子重置，依次施加力矩，打印轨迹",
    ),
    (
        "pendulum#after",
        "示例：\n  ppo-tutor pendulum --seed 0 --actions=-0.5,1.25,2 --json\n  ppo-tutor pendulum --seed 3 --actions -2,-2,2,2 --resets 3",
    ),
    (
        "pendulum:seed",
        "reset(seed=...) 的随机种子，0 到 2^64-1 之间的任意整数",
    ),
    (
        "pendulum:actions",
        "依次施加的力矩，用逗号分隔的小数，单位 N·m（限幅到 [-2, 2]），如 -0.5,1.25；'' 表示只重置",
    ),
    (
        "pendulum:resets",
        "再记录 <次数> 次不带随机种子的重置后的状态（记在 `next_resets` 里）",
    ),
    (
        "pendulum:json",
        "打印一个 JSON 对象，格式与 Gymnasium 的参照轨迹文件相同",
    ),
    // lessons, show
    ("lessons", "按顺序列出所有课，每行一课：`id<TAB>标题`"),
    (
        "show",
        "把一课的某一节（或全部各节）连同实时数值打印成纯文本",
    ),
    (
        "show:id",
        "课的 ID，即 `ppo-tutor lessons` 列出的那个（如 `td-target`）",
    ),
    ("show:step", "要显示的节，从 1 数起；不给则显示全部各节"),
    (
        "show:episodes",
        "显示实时数值之前训练的回合数（显示最后一个回合的那次更新）",
    ),
    ("show:seed", "智能体和环境的随机种子"),
    // train
    (
        "train",
        "在车杆（CartPole-v1）上训练原教程的 PPO（或用 --env Pendulum-v1 训练书中的 PPOContinuous）：进度条、汇总和回报曲线",
    ),
    (
        "train#after",
        "示例：\n  ppo-tutor train\n  ppo-tutor train --seed 3 --json run.json --save agent.safetensors --plot returns.svg\n  ppo-tutor play --load agent.safetensors\n  ppo-tutor train --seeds 0-4 --plot seeds.svg --json seeds.json\n  ppo-tutor train --env Pendulum-v1 --save pendulum.safetensors && ppo-tutor play --load pendulum.safetensors",
    ),
    (
        "train:episodes",
        "训练的回合数（每个回合更新一次）[默认：车杆 500，Pendulum-v1 为 2000]",
    ),
    (
        "train:seed",
        "网络初始化、动作采样和第一次 env.reset 的随机种子",
    ),
    (
        "train:seeds",
        "并行训练多个随机种子（一个范围或一个列表：0-4、1,3,8）：打印每个随机种子最后 50 个回报的均值（Pendulum-v1 为 100 个）及其均值 ± 标准差，并把平均曲线画在各随机种子的范围带上",
    ),
    (
        "train:env_id",
        "Gymnasium 环境 ID，大小写不限：CartPole-v1 和 CartPole-v0（原教程的 PPO）或 Pendulum-v1（书中的 PPOContinuous，一个高斯策略）",
    ),
    ("train:json", "把回报、环境步数和用时以 JSON 写入 <文件>"),
    (
        "train:save",
        "把训练好的智能体存到 <文件>（.safetensors 文件；用 `ppo-tutor play --load` 观看）",
    ),
    (
        "train:plot",
        "把回报曲线及其移动平均画到 <文件>（.png 或 .svg）",
    ),
    (
        "train:x_axis",
        "--plot 的横轴：回合的序号，或每个回合结束时累计的环境时间步（回合长度或采样方式不同的运行，在这个横轴上才能比较）",
    ),
    ("train:x_axis=episodes", "第 0、1、2……个回合"),
    (
        "train:x_axis=steps",
        "从训练开始累计的环境时间步，取在每个回合结束时",
    ),
    ("train:quiet", "不显示进度条和终端里的图：只打印汇总"),
    (
        "train:actor_lr",
        "策略网络的学习率 [默认：车杆 1e-3，Pendulum-v1 为 1e-4]",
    ),
    (
        "train:critic_lr",
        "价值网络的学习率 [默认：车杆 1e-2，Pendulum-v1 为 5e-3]",
    ),
    (
        "train:gamma",
        "折扣因子 γ，取值 (0, 1] [默认：车杆 0.98，Pendulum-v1 为 0.9]",
    ),
    (
        "train:lmbda",
        "GAE 的 λ，取值 [0, 1] [默认：车杆 0.95，Pendulum-v1 为 0.9]",
    ),
    ("train:eps", "截断范围 ε，取值 (0, 1) [默认：0.2]"),
    ("train:epochs", "每次更新训练的轮数 [默认：10]"),
    (
        "train:critic_epochs",
        "价值网络每次更新走的步数，可以设得与策略网络的 --epochs 不同（截断实验室的 `epochs` 实验就这样做）[默认：与策略网络的轮数相同；仅限车杆]",
    ),
    ("train:hidden_dim", "两个网络的隐藏层宽度 [默认：128]"),
    (
        "train:bootstrap_truncation",
        "回合因时限中断时从 V(s') 自举（原教程代码没有；仅限车杆）",
    ),
    (
        "train:normalize_advantage",
        "把优势值归一化到均值 0、标准差 1（原教程代码没有；仅限车杆）",
    ),
    (
        "train:entropy_coef",
        "熵奖励的系数；0 表示关闭（同原教程代码；仅限车杆）",
    ),
    (
        "train:max_grad_norm",
        "对每个网络做梯度裁剪：梯度范数不超过这个值（原教程代码没有；仅限车杆）",
    ),
    (
        "train:target_kl",
        "一次更新中 approx_kl 超过此值的 1.5 倍时就停止后面的轮次（Spinning Up 的做法）；原教程代码没有；仅限车杆",
    ),
    (
        "train:no_clip",
        "去掉截断：策略网络的损失为 −mean(ratio·Â)（截断实验室的实验）；原教程代码没有；仅限车杆",
    ),
    (
        "train:algorithm",
        "更新规则：ppo（原教程代码）或 reinforce（带基线的 REINFORCE：每个回合在 log π·(G_t − V(s_t)) 上走一步，没有比率，没有截断；仅限车杆）",
    ),
    ("train:algorithm=ppo", "原教程的 PPO"),
    ("train:algorithm=reinforce", "以价值网络为基线的 REINFORCE"),
    (
        "train:objective",
        "策略网络的 PPO 目标：clip（原教程的 PPO-截断）、penalty（PPO-惩罚：−mean(ratio·Â) + β·mean(KL(π_old‖π))，每次更新后 β 减半或加倍，使 KL 保持在 --kl-delta 附近）或 line-search（在替代目标的梯度上做受 KL 约束的线搜索，即 TRPO 的约束而不用它的自然梯度：每次更新策略网络只走一步，步长不断减半，直到平均 KL ≤ --kl-delta 且替代目标变好）；仅限车杆",
    ),
    ("train:objective=clip", "PPO-截断，原教程的做法"),
    ("train:objective=penalty", "PPO-惩罚，自适应的 KL 惩罚"),
    (
        "train:objective=line-search",
        "在替代目标的梯度上做受 KL 约束的线搜索（不是 TRPO）",
    ),
    ("train:beta_init", "PPO-惩罚的初始 β [默认：1]"),
    (
        "train:kl_delta",
        "PPO-惩罚的 KL 目标 δ：低于 δ/1.5 时 β 减半，高于 1.5·δ 时加倍；也是线搜索对平均 KL 的上限 [默认：0.01]。不同于 --target-kl（那个是提前停止轮次）",
    ),
    (
        "train:ls_max_step",
        "线搜索沿梯度单位方向的初始步长 α [默认：0.25]",
    ),
    (
        "train:ls_backtracks",
        "线搜索最多把 α 减半几次，之后策略网络保留 θ_old [默认：10]",
    ),
    // lab
    (
        "lab",
        "运行一个截断实验室的实验：只改一个设置，每种取值都跑多个随机种子",
    ),
    (
        "lab:experiment",
        "实验：`eps`、`epochs`、`actor-lr`、`target-kl`、`reinforce`、`critic-lr`、`hidden-dim`、`gamma`、`lmbda` 或 `proximal`（不给则列出全部）",
    ),
    (
        "lab:seeds",
        "每种取值都要跑的随机种子：数字和范围，如 0-4 或 0,3,7",
    ),
    ("lab:episodes", "每次运行的回合数"),
    (
        "lab:json",
        "把每次运行的回报、范围带和统计量以 JSON 写入 <文件>",
    ),
    ("lab:plot", "把各取值的范围带画到 <文件>（.png 或 .svg）"),
    ("lab:quiet", "只打印表格（不显示进度条，不画图）"),
    // trust-region
    (
        "trust-region",
        "测一测 PPO 的替代目标在多大范围内可信：沿最近一批数据的梯度走越来越长的步，每步给出 KL、预测的和实际的回报变化",
    ),
    (
        "trust-region#after",
        "示例：\n  ppo-tutor trust-region\n  ppo-tutor trust-region --seed 3 --train-episodes 60 --steps 0,0.1,0.4,1.6 --eval-episodes 200\n  ppo-tutor trust-region --json > probe.json",
    ),
    ("trust-region:seed", "训练和留出回合的随机种子"),
    (
        "trust-region:train_episodes",
        "先把原教程的 PPO 训练多少个回合，再探测它最近的一批数据",
    ),
    (
        "trust-region:eval_episodes",
        "每个步长用来评估的留出回合数（至少 2）[默认：150]",
    ),
    (
        "trust-region:steps",
        "步长 α（参数空间中的 L2 范数），用逗号分隔，如 0,0.1,0.4,1.6 [默认：0,0.025,0.05,0.1,0.2,0.3,0.4,0.6,0.8,1.2,1.6,3.2]",
    ),
    (
        "trust-region:json",
        "在标准输出上以 JSON 打印探测结果，而不是表格",
    ),
    // play
    (
        "play",
        "观看保存下来的智能体（`train --save`）让杆保持平衡，或让倒立摆完成起摆",
    ),
    (
        "play#after",
        "示例：\n  ppo-tutor train --save agent.safetensors && ppo-tutor play --load agent.safetensors\n  ppo-tutor train --env Pendulum-v1 --save pendulum.safetensors && ppo-tutor play --load pendulum.safetensors",
    ),
    (
        "play:load",
        "由 `ppo-tutor train --save` 写出的智能体文件（车杆或 Pendulum-v1：文件里写明是哪个）",
    ),
    ("play:episodes", "要运行的回合数"),
    ("play:seed", "第一次重置和动作采样的随机种子"),
    (
        "play:env_id",
        "Gymnasium 环境 ID，大小写不限 [默认：检查点里的，CartPole-v1 或 Pendulum-v1]；CartPole-v0 用 200 步的时限运行车杆智能体",
    ),
    (
        "play:greedy",
        "选概率最大的动作，而不是像训练时那样采样（Pendulum-v1 的智能体总是施加它的均值力矩 μ）",
    ),
    (
        "play:delay_ms",
        "每帧的毫秒数，不小于 0 [默认：车杆 20（Gymnasium 的 50 fps），Pendulum-v1 为 33（30 fps）]",
    ),
    ("play:no_render", "只打印每个回合的回报，不显示动画"),
    // replay
    (
        "replay",
        "重新运行记录下来的 PyTorch 更新（ppo_update_pytorch.json 或其连续动作版），并打印本教程算出的结果",
    ),
    (
        "replay#after",
        "<文件> 的格式是 ppo_update_pytorch.json（由 ppo_fixtures.py 生成）、ppo_penalty_update_pytorch.json（`ppo_fixtures.py --objective penalty`：每个用例带 `\"objective\": \"penalty\"`，`hyper` 里多出 `beta` 和 `kl_target`，更新从 expected.beta_before 开始）或 ppo_continuous_update_pytorch.json（由 ppo_continuous_fixtures.py 生成；其策略网络有 fc_mu 和 fc_std）：`{\"cases\": [{\"hyper\", \"weights_before\", \"batch\"}, ...]}`。\n\n示例：\n  ppo-tutor replay tests/fixtures/ppo_update_pytorch.json --json > ours.json\n  ppo-tutor replay tests/fixtures/ppo_penalty_update_pytorch.json --json > ours_penalty.json\n  ppo-tutor replay tests/fixtures/ppo_continuous_update_pytorch.json --json > ours_continuous.json",
    ),
    ("replay:file", "记录下来的更新"),
    (
        "replay:json",
        "打印 `{\"cases\": [...]}`，键名和形状与参照文件相同，而不是表格",
    ),
    // grade, watch, reset, init
    (
        "grade",
        "为某个练习（或全部练习）的解答评分：各项检查、第一个失败的输入、提示",
    ),
    (
        "grade#after",
        "编译好的程序缓存在 $PPO_TUTOR_GRADE_CACHE，默认是系统临时文件夹里的 `ppo-tutor-grade`（例如 `/tmp/ppo-tutor-grade`）：ppo_losses 所需的 candle 构建（约 380 MB，只编译一次，双核约 2 分钟），以及每个练习最近用过的 4 个构建（每个约 0.5 MB，ppo_losses 的约 5 MB）。删除这个文件夹是安全的：需要时会重新构建。",
    ),
    (
        "grade:exercise",
        "练习（它的函数名，如 compute_advantage）；不给则评全部练习",
    ),
    (
        "grade:file",
        "评这个文件，而不是起始文件所在的路径（lessons/NN-slug/exercise.rs，ppo_losses 则是 exercise_candle.rs）",
    ),
    (
        "grade:time_limit",
        "学习者的代码跑完一个练习的全部用例最多可用的秒数（至少 1）",
    ),
    (
        "watch",
        "每次保存练习文件时重新评分，通过后接着做下一个练习",
    ),
    (
        "watch:exercise",
        "从哪个练习开始；默认是课程顺序中第一个还没通过的练习",
    ),
    (
        "watch:time_limit",
        "学习者的代码跑完一个练习的全部用例最多可用的秒数（至少 1）",
    ),
    (
        "reset",
        "恢复一个练习的起始文件（lessons/NN-slug/exercise.rs）",
    ),
    (
        "reset:exercise",
        "要恢复起始代码的练习：课的文件里还有别的练习时只恢复它的函数，否则恢复整个文件；改动过的文件会先另存为原文件名加 .bak",
    ),
    (
        "init",
        "把每个练习的起始文件写进一个文件夹，以便在克隆的仓库之外做练习",
    ),
    (
        "init:dir",
        "写入练习的文件夹（需要时会创建）；默认是当前文件夹。之后在那里运行 `grade`、`watch` 和本教程",
    ),
    // dev
    ("dev", "重新生成课程内容的开发者命令（`dev notebooks`）"),
    (
        "dev.notebooks",
        "从各课和 notebooks/src/ 重新生成 notebooks/*.ipynb（单元格及其输出）",
    ),
    (
        "dev.notebooks#long",
        "从各课和 notebooks/src/ 里的配方重新生成 notebooks/*.ipynb（单元格及其输出），每个单元格都在 evcxr 引擎上执行（第一次运行要在其中编译 ppo-tutor 和 candle：需要几分钟）。\n\n需要 `notebook-runner` 特性；在仓库里运行：\n  `cargo run --features notebook-runner -- dev notebooks [课]...`\n然后用 `cargo test --test notebook_code` 和 `cargo test --features full-tests --test notebooks` 检查结果。",
    ),
    (
        "dev.notebooks:lessons",
        "只处理文件夹名包含这些字符串之一的课（`07`、`gae`）；不给则处理全部各课",
    ),
    (
        "dev.notebook-code",
        "从各课和 notebooks/src/ 重新生成 tests/notebook_code/（每个笔记本的代码，写成普通 Rust）",
    ),
    (
        "dev.notebook-code#long",
        "从各课和 notebooks/src/ 里的配方重新生成 tests/notebook_code/{en,zh}/：每个笔记本的代码单元格按顺序写成一个 Rust 函数，由 `cargo test --test notebook_code` 对照 ppo-tutor 的库编译并运行，不需要 evcxr。不需要任何特性；`dev notebooks` 也会写出它们。在仓库里运行：\n  `cargo run -- dev notebook-code`",
    ),
    (
        "dev.notebook-markdown",
        "按各课重写 notebooks/*.ipynb 的 markdown 单元格，保留每个代码单元格及其输出（不需要 evcxr）",
    ),
    (
        "dev.notebook-markdown#long",
        "按各课重写 notebooks/*.ipynb 和 notebooks/zh/*.ipynb 的 markdown 单元格，保留每个代码单元格及其保存的输出：适用于改了某课的文字或锚点引用的代码的情况，几秒钟完成，不需要 evcxr。代码单元格与配方不一致的笔记本会被拒绝（它们的输出已经过时：请运行 `dev notebooks`）。在仓库里运行：\n  `cargo run -- dev notebook-markdown`",
    ),
    (
        "dev.screenshots",
        "用应用自己的屏幕重新绘制 `README.md` 里的图片（assets/screens/*.png）",
    ),
    (
        "dev.screenshots#long",
        "用应用自己的屏幕重新绘制 `README.md` 里的图片 assets/screens/{en,zh}-{lesson,training,exercise}.png：每张都像教程那样画在 160×50 的屏幕上（真实的训练，随机种子 0；真实的评分），再用 assets/fonts/ 里的字体画成图片。已提交的图片与应用现在画出的不同时，`cargo test --test cli screenshots` 会失败。在仓库里运行：\n  `cargo run --release -- dev screenshots`",
    ),
];

/// Value names in Chinese, keyed by the name the code gives (or clap derives from the id).
pub const VALUE_NAMES_ZH: &[(&str, &str)] = &[
    ("ACTIONS", "动作"),
    ("ACTOR_LR", "学习率"),
    ("ALGORITHM", "算法"),
    ("BETA_INIT", "β"),
    ("COMMAND", "命令"),
    ("CRITIC_EPOCHS", "步数"),
    ("CRITIC_LR", "学习率"),
    ("DELAY_MS", "毫秒"),
    ("DIR", "文件夹"),
    ("ENTROPY_COEF", "系数"),
    ("ENV_ID", "环境"),
    ("EPISODES", "回合数"),
    ("EPOCHS", "轮数"),
    ("EPS", "ε"),
    ("EVAL_EPISODES", "回合数"),
    ("EXERCISE", "练习"),
    ("EXPERIMENT", "实验"),
    ("FILE", "文件"),
    ("GAMMA", "γ"),
    ("HIDDEN_DIM", "宽度"),
    ("ID", "课"),
    ("KL_DELTA", "δ"),
    ("LANG", "语言"),
    ("LESSONS", "课"),
    ("LIST", "列表"),
    ("LMBDA", "λ"),
    ("LS_BACKTRACKS", "次数"),
    ("LS_MAX_STEP", "α"),
    ("MAX_GRAD_NORM", "范数"),
    ("MAX_STEPS", "步数"),
    ("MODE", "方式"),
    ("N", "个数"),
    ("OBJECTIVE", "目标"),
    ("PATH", "路径"),
    ("POLICY", "策略"),
    ("RESETS", "次数"),
    ("SECS", "秒数"),
    ("SEED", "种子"),
    ("STEP", "节"),
    ("TARGET_KL", "KL"),
    ("TORQUES", "力矩"),
    ("TRAIN_EPISODES", "回合数"),
    ("X_AXIS", "横轴"),
];

/// Looks up `key` in `table`.
fn find(table: &[(&'static str, &'static str)], key: &str) -> Option<&'static str> {
    table.iter().find(|(k, _)| *k == key).map(|(_, v)| *v)
}

/// What the walk asks for each text it meets: its key and its English; the answer is the
/// text to print (the Chinese), or `None` to keep the English.
pub(crate) trait Lookup {
    /// The translation of the text `english` with id `key`.
    fn text(&mut self, key: &str, english: &str) -> Option<String>;
    /// The translation of the value name `name`.
    fn value_name(&mut self, name: &str) -> Option<&'static str>;
}

/// The catalogue as a [`Lookup`].
struct Catalogue;

impl Lookup for Catalogue {
    fn text(&mut self, key: &str, _english: &str) -> Option<String> {
        find(HELP_ZH, key).map(str::to_string)
    }
    fn value_name(&mut self, name: &str) -> Option<&'static str> {
        find(VALUE_NAMES_ZH, name)
    }
}

/// `cmd` (the whole `ppo-tutor` command) with every text clap prints in Chinese.
#[must_use]
pub fn localise(cmd: Command) -> Command {
    walk_tree(cmd, &mut Catalogue)
}

/// Builds `cmd` (so clap's own flags and `help` subcommands exist) and walks it with
/// `lookup`.
pub(crate) fn walk_tree(mut cmd: Command, lookup: &mut dyn Lookup) -> Command {
    cmd.build();
    walk(cmd, None, lookup)
}

/// The key of the command named `name` under `parent` (`None` at the top).
fn command_key(parent: Option<&str>, name: &str) -> String {
    match parent {
        None => name.to_string(),
        Some("") => name.to_string(),
        Some(p) => format!("{p}.{name}"),
    }
}

/// Translates one (built) command and its subcommands. `parent` is the key of the
/// command above (`Some("")` below the top), `None` for the top.
fn walk(mut cmd: Command, parent: Option<&str>, lookup: &mut dyn Lookup) -> Command {
    let name = cmd.get_name().to_string();
    let is_help = parent.is_some() && name == "help";
    let key = if is_help {
        "*help".to_string()
    } else {
        command_key(parent, &name)
    };
    // Below the top, paths start at the subcommand's own name.
    let below = match parent {
        None => String::new(),
        // clap's `help` lists copies of its siblings: they take the siblings' keys.
        Some(p) if is_help => p.to_string(),
        Some(_) => key.clone(),
    };

    if let Some(about) = cmd.get_about().map(ToString::to_string)
        && let Some(zh) = lookup.text(&key, &about)
    {
        cmd = cmd.about(zh);
    }
    if let Some(long) = cmd.get_long_about().map(ToString::to_string)
        && let Some(zh) = lookup.text(&format!("{key}#long"), &long)
    {
        cmd = cmd.long_about(zh);
    }
    if let Some(after) = cmd.get_after_help().map(ToString::to_string)
        && let Some(zh) = lookup.text(&format!("{key}#after"), &after)
    {
        cmd = cmd.after_help(zh);
    }
    if let Some(after) = cmd.get_after_long_help().map(ToString::to_string)
        && let Some(zh) = lookup.text(&format!("{key}#after_long"), &after)
    {
        cmd = cmd.after_long_help(zh);
    }

    cmd = cmd.mut_args(|arg| localise_arg(arg, &key, lookup));
    if let Some(zh) = lookup.value_name("COMMAND") {
        cmd = cmd.subcommand_value_name(zh);
    }
    cmd = cmd.mut_subcommands(|sub| walk(sub, Some(&below), lookup));

    // The sections under Chinese headings, each only when it has something to show.
    let subcommands = cmd.get_subcommands().any(|s| !s.is_hide_set());
    let positionals = cmd.get_positionals().any(|a| !a.is_hide_set());
    let options = cmd
        .get_arguments()
        .any(|a| !a.is_positional() && !a.is_hide_set());
    let mut template = String::from("{before-help}{about-with-newline}\n用法：{usage}");
    if subcommands {
        template.push_str("\n\n命令：\n{subcommands}");
    }
    if positionals {
        template.push_str("\n\n参数：\n{positionals}");
    }
    if options {
        template.push_str("\n\n选项：\n{options}");
    }
    template.push_str("{after-help}");
    cmd = cmd.help_template(template);
    // clap writes `[OPTIONS]` itself: the usage line is rendered once and given back.
    let usage = cmd.render_usage().to_string();
    let usage = usage
        .trim()
        .strip_prefix("Usage:")
        .unwrap_or(&usage)
        .trim()
        .replace("[OPTIONS]", "[选项]");
    cmd.override_usage(usage)
}

/// Translates one argument of the command with key `cmd_key`.
fn localise_arg(mut arg: clap::Arg, cmd_key: &str, lookup: &mut dyn Lookup) -> clap::Arg {
    let id = arg.get_id().as_str().to_string();
    let own = matches!(id.as_str(), "help" | "version");
    let mut key = if own || arg.is_global_set() {
        format!("*:{id}")
    } else {
        format!("{cmd_key}:{id}")
    };
    if id == "help" && arg.get_long_help().is_some() {
        key.push('+');
    }
    let takes_values = arg.get_action().takes_values();

    // Defaults and possible values: clap writes `[default: ...]` and `Possible values:`
    // itself, so they are hidden and said in Chinese after the help.
    let defaults: Vec<String> = arg
        .get_default_values()
        .iter()
        .map(|v| v.to_string_lossy().into_owned())
        .collect();
    let default = (takes_values && !arg.is_hide_default_value_set() && !defaults.is_empty())
        .then(|| format!("[默认：{}]", defaults.join(" ")));
    let values: Vec<(String, Option<String>)> =
        if takes_values && !arg.is_hide_possible_values_set() {
            arg.get_possible_values()
                .iter()
                .filter(|v| !v.is_hide_set())
                .map(|v| {
                    let name = v.get_name().to_string();
                    let help = v.get_help().map(|h| {
                        lookup
                            .text(&format!("{key}={name}"), &h.to_string())
                            .unwrap_or_else(|| h.to_string())
                    });
                    (name, help)
                })
                .collect()
        } else {
            Vec::new()
        };

    let help = arg.get_help().map(|h| {
        lookup
            .text(&key, &h.to_string())
            .unwrap_or_else(|| h.to_string())
    });
    let long = arg.get_long_help().map(|h| {
        lookup
            .text(&format!("{key}#long"), &h.to_string())
            .unwrap_or_else(|| h.to_string())
    });

    // The short help: the text, the values' names, the default.
    let mut short = help.clone().unwrap_or_default();
    if !values.is_empty() {
        let names: Vec<&str> = values.iter().map(|(n, _)| n.as_str()).collect();
        push_spec(&mut short, &format!("[可选值：{}]", names.join("、")));
    }
    if let Some(d) = &default {
        push_spec(&mut short, d);
    }
    // The long help (only where clap would have one): the text, each value with its
    // help, the default, on lines of their own.
    let described = values.iter().any(|(_, h)| h.is_some());
    if long.is_some() || described {
        let mut text = long.or(help).unwrap_or_default();
        if !values.is_empty() {
            let width = values.iter().map(|(n, _)| n.len()).max().unwrap_or(0);
            text.push_str("\n\n可选值：");
            for (name, help) in &values {
                match help {
                    Some(h) => text.push_str(&format!(
                        "\n- {name}：{:pad$}{h}",
                        "",
                        pad = width - name.len()
                    )),
                    None => text.push_str(&format!("\n- {name}")),
                }
            }
        }
        if let Some(d) = &default {
            text.push_str("\n\n");
            text.push_str(d);
        }
        arg = arg.long_help(StyledStr::from(text));
    }
    if !short.is_empty() {
        arg = arg.help(StyledStr::from(short));
    }
    if default.is_some() {
        arg = arg.hide_default_value(true);
    }
    if !values.is_empty() {
        arg = arg.hide_possible_values(true);
    }
    if takes_values {
        let names: Vec<String> = match arg.get_value_names() {
            Some(names) => names.iter().map(ToString::to_string).collect(),
            None => vec![id.to_ascii_uppercase()],
        };
        let zh: Option<Vec<&'static str>> = names.iter().map(|n| lookup.value_name(n)).collect();
        if let Some(zh) = zh {
            // clap's `unicode` feature measures a Chinese character as two columns, so the
            // help column lines up after Chinese value names too.
            arg = arg.value_names(zh);
        }
    }
    arg
}

/// Appends `spec` (`[默认：…]`) to a short help, after a space when there is text.
fn push_spec(text: &mut String, spec: &str) {
    if !text.is_empty() {
        text.push(' ');
    }
    text.push_str(spec);
}

/// The identifiers a user types: every subcommand's name, every argument's id and long
/// name, every possible value and its aliases (what a Chinese screen may quote as code).
pub fn identifiers(cmd: &Command, out: &mut std::collections::BTreeSet<String>) {
    out.insert(cmd.get_name().to_string());
    for arg in cmd.get_arguments() {
        out.insert(arg.get_id().to_string());
        if let Some(long) = arg.get_long() {
            out.insert(long.to_string());
        }
        for value in arg.get_possible_values() {
            out.extend(value.get_name_and_aliases().map(ToString::to_string));
        }
    }
    for sub in cmd.get_subcommands() {
        identifiers(sub, out);
    }
}

/// The English words in `text` outside code spans, flags, file names, formulas, all-caps
/// names, the reviewed names of [`ppo_engine::i18n::ALLOWED_WORDS`] and `allowed`.
#[cfg(test)]
pub(crate) fn english_words(
    text: &str,
    allowed: &std::collections::BTreeSet<String>,
) -> Vec<String> {
    ppo_engine::i18n::english_words(text, allowed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::CommandFactory as _;
    use std::collections::BTreeSet;

    /// Records every key the walk asks for.
    #[derive(Default)]
    struct Recorder {
        missing: Vec<String>,
        used: BTreeSet<String>,
        missing_names: BTreeSet<String>,
        used_names: BTreeSet<String>,
    }

    impl Lookup for Recorder {
        fn text(&mut self, key: &str, english: &str) -> Option<String> {
            self.used.insert(key.to_string());
            let found = find(HELP_ZH, key);
            if found.is_none() {
                let line = format!("(\"{key}\", \"\"), // {english:?}");
                if !self.missing.contains(&line) {
                    self.missing.push(line);
                }
            }
            found.map(str::to_string)
        }
        fn value_name(&mut self, name: &str) -> Option<&'static str> {
            self.used_names.insert(name.to_string());
            let found = find(VALUE_NAMES_ZH, name);
            if found.is_none() {
                self.missing_names.insert(name.to_string());
            }
            found
        }
    }

    /// Every help text of every command (hidden ones too) has a Chinese entry, and every
    /// entry is a help text that exists.
    #[test]
    fn every_help_text_has_its_chinese_and_every_entry_is_used() {
        let mut recorder = Recorder::default();
        let _ = walk_tree(crate::cli::Cli::command(), &mut recorder);
        let unused: Vec<&str> = HELP_ZH
            .iter()
            .map(|(k, _)| *k)
            .filter(|k| !recorder.used.contains(*k))
            .collect();
        let unused_names: Vec<&str> = VALUE_NAMES_ZH
            .iter()
            .map(|(k, _)| *k)
            .filter(|k| !recorder.used_names.contains(*k))
            .collect();
        assert!(
            recorder.missing.is_empty()
                && recorder.missing_names.is_empty()
                && unused.is_empty()
                && unused_names.is_empty(),
            "help texts without Chinese:\n{}\nvalue names without Chinese: {:?}\n\
             entries whose key no longer exists: {unused:?}\nunused value names: {unused_names:?}",
            recorder.missing.join("\n"),
            recorder.missing_names,
        );
        let mut keys: Vec<&str> = HELP_ZH.iter().map(|(k, _)| *k).collect();
        keys.sort_unstable();
        let before = keys.len();
        keys.dedup();
        assert_eq!(before, keys.len(), "a key is in the catalogue twice");
    }

    /// The paths of every command under `cmd` (hidden ones too; not clap's `help`).
    fn paths(cmd: &Command, prefix: &[String], out: &mut Vec<Vec<String>>) {
        for sub in cmd.get_subcommands().filter(|s| s.get_name() != "help") {
            let mut path = prefix.to_vec();
            path.push(sub.get_name().to_string());
            out.push(path.clone());
            paths(sub, &path, out);
        }
    }

    /// Every help in Chinese (`-h`, `--help` and `help COMMAND`, of the program and of every
    /// subcommand, `dev`'s too) has no English word outside code and identifiers, and has
    /// the Chinese headings.
    #[test]
    fn every_chinese_help_is_chinese() {
        // Built, so that clap's own `help` subcommand and flags are among the identifiers.
        let mut english = crate::cli::Cli::command();
        english.build();
        let mut allowed = BTreeSet::new();
        identifiers(&english, &mut allowed);
        let mut all = vec![Vec::new()];
        paths(&english, &[], &mut all);
        assert!(all.len() > 10, "{all:?}");
        let mut problems = Vec::new();
        for path in &all {
            let mut lines: Vec<Vec<String>> = ["-h", "--help"]
                .iter()
                .map(|flag| {
                    let mut line = vec!["ppo-tutor".to_string()];
                    line.extend(path.iter().cloned());
                    line.push((*flag).to_string());
                    line
                })
                .collect();
            if !path.is_empty() {
                let mut line = vec!["ppo-tutor".to_string()];
                line.extend(path[..path.len() - 1].iter().cloned());
                line.push("help".to_string());
                line.push(path[path.len() - 1].clone());
                lines.push(line);
            }
            for line in lines {
                let mut cmd = localise(crate::cli::Cli::command());
                let text = match cmd.try_get_matches_from_mut(&line) {
                    Err(e) if e.kind() == clap::error::ErrorKind::DisplayHelp => {
                        e.render().to_string()
                    }
                    other => {
                        problems.push(format!("{line:?}: no help: {other:?}"));
                        continue;
                    }
                };
                let words = english_words(&text, &allowed);
                if !words.is_empty() {
                    problems.push(format!("{line:?}: English {words:?} in:\n{text}"));
                }
                if !text.contains("用法：") || !text.contains("选项：") {
                    problems.push(format!("{line:?}: no Chinese headings in:\n{text}"));
                }
            }
        }
        assert!(problems.is_empty(), "{}", problems.join("\n\n"));
    }

    /// The catalogue uses the course's terms: no `avoid` word of `lessons/glossary.toml`
    /// (its `allow` phrases, such as 梯度裁剪, taken out first, as `tests/i18n.rs` does).
    #[test]
    fn the_catalogue_keeps_to_the_glossary() -> Result<(), Box<dyn std::error::Error>> {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("lessons/glossary.toml");
        let glossary: toml::Table = std::fs::read_to_string(path)?.parse()?;
        let terms = glossary
            .get("term")
            .and_then(|t| t.as_array())
            .ok_or("no [[term]] in the glossary")?;
        let mut problems = Vec::new();
        for term in terms {
            let list = |key: &str| -> Vec<&str> {
                term.get(key)
                    .and_then(|v| v.as_array())
                    .map(|a| a.iter().filter_map(|s| s.as_str()).collect())
                    .unwrap_or_default()
            };
            let (avoid, allow) = (list("avoid"), list("allow"));
            for (key, text) in HELP_ZH.iter().chain(VALUE_NAMES_ZH) {
                let rest = allow
                    .iter()
                    .fold((*text).to_string(), |acc, phrase| acc.replace(phrase, " "));
                for word in avoid.iter().filter(|w| rest.contains(**w)) {
                    problems.push(format!("{key}: {word}"));
                }
            }
        }
        assert!(problems.is_empty(), "avoided words: {problems:?}");
        Ok(())
    }

    /// The word check itself: it finds English prose and lets code through.
    #[test]
    fn the_word_check_tells_prose_from_code() {
        let allowed: BTreeSet<String> = ["train".to_string()].into();
        assert_eq!(
            english_words("Print help（见 --help）", &allowed),
            vec!["Print", "help"]
        );
        assert!(
            english_words(
                "用 `cargo run -- dev` 运行 ppo-tutor train --seed 3 run.json PPO CartPole-v1 −mean(ratio·Â)",
                &allowed
            )
            .is_empty()
        );
    }
}
