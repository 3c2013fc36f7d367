//! Judging the learner's answers: losses and weight gradients against the reference's,
//! the report's lines, the diagnosis of a wrong answer from the catalogue of mistakes
//! (one per loss), and the training check.

use std::time::Duration;

use super::Learner;
use super::cases::{Case, Cases};
use super::mistakes::{MISTAKES, Mistake, Part};
use super::project::Answer;
use super::protocol::{self, Inputs, LossesFn, Reply};
use super::{
    ACTOR_PARAMS, CRITIC_PARAMS, Gradients, LEARNS_AT, REFERENCE, REFERENCE_MEAN, TRAIN_EPISODES,
    TRAIN_SEED, TRAIN_WINDOW, gradients, train,
};
use crate::grade::report::{CheckStatus, Failure, Problem};
use crate::grade::value::Arg;
use crate::ppo::train::mean_last;

/// The hint when no known mistake explains a wrong answer.
const HINT: &str = "Compare with the seed line by line: log_probs = log(gather(probs, \
    actions)), ratio = exp(log_probs - old_log_probs), surr2 = clamp(ratio, 1 - eps, 1 + eps) \
    * advantage, actor_loss = mean(-min(surr1, surr2)), critic_loss = mean((values - \
    td_target.detach())²).";

/// What a losses function gave on one case, with the weight gradients it implies.
#[derive(Debug, Clone)]
pub(super) struct Outcome {
    reply: Reply,
    grads: Gradients,
}

pub(super) fn outcome(case: &Case, reply: Reply) -> Option<Outcome> {
    let grads = gradients(case, &reply).ok()?;
    Some(Outcome { reply, grads })
}

/// `|got − want| ≤ 1e-5 + 1e-4·|want|` (false for NaN).
pub(super) fn close(got: f32, want: f32) -> bool {
    (got - want).abs() <= 1e-5 + 1e-4 * want.abs()
}

/// The first element (parameter, index) where `got` is not within `1e-5 + 1e-3·max|want|`
/// of `want`, per parameter.
pub(super) fn first_difference(got: &[Vec<f32>], want: &[Vec<f32>]) -> Option<(usize, usize)> {
    want.iter().zip(got).enumerate().find_map(|(p, (w, g))| {
        let scale = w.iter().fold(0.0_f32, |m, x| m.max(x.abs()));
        let tol = 1e-5 + 1e-3 * scale;
        w.iter()
            .zip(g)
            .position(|(w, g)| (g - w).abs().partial_cmp(&tol) != Some(std::cmp::Ordering::Less))
            .map(|i| (p, i))
    })
}

impl Outcome {
    fn loss_ok(&self, want: &Self, part: Part) -> bool {
        match part {
            Part::Actor => close(self.reply.actor_loss, want.reply.actor_loss),
            Part::Critic => close(self.reply.critic_loss, want.reply.critic_loss),
        }
    }

    fn grads_ok(&self, want: &Self, part: Part) -> bool {
        match part {
            Part::Actor => first_difference(&self.grads.actor, &want.grads.actor).is_none(),
            Part::Critic => first_difference(&self.grads.critic, &want.grads.critic).is_none(),
        }
    }

    pub(super) fn agrees(&self, want: &Self, part: Part) -> bool {
        self.loss_ok(want, part) && self.grads_ok(want, part)
    }
}

/// What a report line checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// Both losses' values.
    Losses,
    /// The weight gradients.
    Gradients,
}

/// One line of the report and the cases it covers (indices into the flat case list).
pub(super) struct Check {
    pub(super) name: String,
    kind: Kind,
    pub(super) cases: Vec<usize>,
}

/// The report's lines before training, over `cases` flattened in order.
pub(super) fn checks(cases: &Cases) -> Vec<Check> {
    let (f, r, e) = (cases.fixture.len(), cases.random.len(), cases.edge.len());
    let epochs: Vec<String> = super::cases::FIXTURE_EPOCHS
        .iter()
        .map(|k| (k + 1).to_string())
        .collect();
    vec![
        Check {
            name: format!(
                "losses on the recorded PyTorch episodes, epochs {}",
                epochs.join(", ")
            ),
            kind: Kind::Losses,
            cases: (0..f).collect(),
        },
        Check {
            name: format!("losses on {r} seeded random batches"),
            kind: Kind::Losses,
            cases: (f..f + r).collect(),
        },
        Check {
            name: "losses on edge cases (a single step, only negative advantages with every \
                   ratio outside 1 ± ε, every ratio exactly 1)"
                .into(),
            kind: Kind::Losses,
            cases: (f + r..f + r + e).collect(),
        },
        Check {
            name: "gradients into the actor's and the critic's weights".into(),
            kind: Kind::Gradients,
            cases: (0..f + r + e).collect(),
        },
    ]
}

/// The learner's, the reference's and the diagnosed mistakes' outcomes on every case.
pub(super) struct Judge<'a> {
    all: &'a [&'a Case],
    answers: &'a [Answer],
    reference: Vec<Option<Outcome>>,
    learner: Vec<Option<Outcome>>,
    /// The diagnosis for the actor loss, then for the critic loss.
    diagnosis: [Option<&'static Mistake>; 2],
}

fn part_index(part: Part) -> usize {
    match part {
        Part::Actor => 0,
        Part::Critic => 1,
    }
}

impl<'a> Judge<'a> {
    pub(super) fn new(all: &'a [&'a Case], answers: &'a [Answer]) -> Self {
        let run = |f: LossesFn| -> Vec<Option<Outcome>> {
            all.iter()
                .map(|c| outcome(c, protocol::evaluate(f, &c.inputs).ok()?))
                .collect()
        };
        let reference = run(REFERENCE);
        let learner = answers
            .iter()
            .zip(all)
            .map(|(a, c)| match a {
                Answer::Reply(r) => outcome(c, r.clone()),
                _ => None,
            })
            .collect();
        let mut judge = Self {
            all,
            answers,
            reference,
            learner,
            diagnosis: [None, None],
        };
        for part in [Part::Actor, Part::Critic] {
            judge.diagnosis[part_index(part)] = judge.diagnose(part, &run);
        }
        judge
    }

    /// The known mistake in `part` that best explains the learner's outcomes: among those
    /// reproducing at least one wrong outcome, the one agreeing on the most cases.
    fn diagnose(
        &self,
        part: Part,
        run: &dyn Fn(LossesFn) -> Vec<Option<Outcome>>,
    ) -> Option<&'static Mistake> {
        let wrong: Vec<bool> = self
            .learner
            .iter()
            .zip(&self.reference)
            .map(|(l, r)| matches!((l, r), (Some(l), Some(r)) if !l.agrees(r, part)))
            .collect();
        if !wrong.contains(&true) {
            return None;
        }
        let mut best: Option<(&'static Mistake, usize)> = None;
        for mistake in MISTAKES.iter().filter(|m| m.part == part) {
            let theirs = run(mistake.answer);
            let agrees: Vec<bool> = self
                .learner
                .iter()
                .zip(&theirs)
                .map(|(l, m)| matches!((l, m), (Some(l), Some(m)) if l.agrees(m, part)))
                .collect();
            let explains = agrees.iter().zip(&wrong).any(|(a, w)| *a && *w);
            let score = agrees.iter().filter(|a| **a).count();
            if explains && best.is_none_or(|(_, b)| score > b) {
                best = Some((mistake, score));
            }
        }
        best.map(|(m, _)| m)
    }

    pub(super) fn any_diagnosis(&self) -> Option<&'static Mistake> {
        self.diagnosis.iter().flatten().next().copied()
    }

    /// A check's status and the mistake its hint names.
    pub(super) fn status(&self, check: &Check) -> (CheckStatus, Option<String>) {
        for &i in &check.cases {
            let found = match &self.answers[i] {
                Answer::Reply(_) => match (&self.learner[i], &self.reference[i]) {
                    (Some(l), Some(r)) => self.wrong(check.kind, l, r),
                    _ => Some((
                        Problem::Crashed(
                            "the gradients could not be carried to the weights".into(),
                        ),
                        String::new(),
                        String::new(),
                        String::new(),
                        (HINT.to_string(), None),
                    )),
                },
                Answer::NotRun => {
                    let why = "an earlier case stopped the program".to_string();
                    return (CheckStatus::NotRun(why), None);
                }
                other => Some(problem(other)),
            };
            let Some((problem, expected, got, detail, (hint, mistake))) = found else {
                continue;
            };
            let failure = Failure {
                problem,
                input: show_inputs(&self.all[i].inputs),
                expected,
                got,
                detail,
                hint,
            };
            return (CheckStatus::Failed(Box::new(failure)), mistake);
        }
        (CheckStatus::Passed, None)
    }

    /// How `got` differs from `want` for a check of `kind`, if it does.
    fn wrong(&self, kind: Kind, got: &Outcome, want: &Outcome) -> Option<Found> {
        let part = match kind {
            Kind::Losses => [Part::Actor, Part::Critic]
                .into_iter()
                .find(|&p| !got.loss_ok(want, p))?,
            Kind::Gradients => [Part::Actor, Part::Critic]
                .into_iter()
                .find(|&p| !got.grads_ok(want, p))?,
        };
        let hint = self.hint(part, kind);
        Some(match kind {
            Kind::Losses => {
                let show = |o: &Outcome| {
                    format!(
                        "actor_loss = {:?}, critic_loss = {:?}",
                        o.reply.actor_loss, o.reply.critic_loss
                    )
                };
                let which = match part {
                    Part::Actor => "the actor loss differs",
                    Part::Critic => "the critic loss differs",
                };
                (Problem::Wrong, show(want), show(got), which.into(), hint)
            }
            Kind::Gradients => {
                let (names, g, w, loss) = match part {
                    Part::Actor => (
                        ACTOR_PARAMS,
                        &got.grads.actor,
                        &want.grads.actor,
                        "actor_loss",
                    ),
                    Part::Critic => (
                        CRITIC_PARAMS,
                        &got.grads.critic,
                        &want.grads.critic,
                        "critic_loss",
                    ),
                };
                let (p, i) = first_difference(g, w).unwrap_or((0, 0));
                let show = |v: &[Vec<f32>]| {
                    let values = v.get(p).cloned().unwrap_or_default();
                    format!("∂{loss}/∂{} = {}", names[p], Arg::F32s(values).show())
                };
                let at = |v: &[Vec<f32>]| v.get(p).and_then(|x| x.get(i)).copied().unwrap_or(0.0);
                let detail = format!("{}[{i}]: expected {:?}, got {:?}", names[p], at(w), at(g));
                (Problem::Wrong, show(w), show(g), detail, hint)
            }
        })
    }

    /// The hint for a wrong `part`, and the mistake it names.
    fn hint(&self, part: Part, kind: Kind) -> (String, Option<String>) {
        match self.diagnosis[part_index(part)] {
            Some(m) => (m.hint.to_string(), Some(m.id.to_string())),
            None if kind == Kind::Gradients => (GRADIENT_HINT.to_string(), None),
            None => (HINT.to_string(), None),
        }
    }
}

/// The hint when the losses are right but their gradients are not, and no known mistake
/// explains it.
const GRADIENT_HINT: &str = "The losses have the right values but the wrong gradients: \
    something is cut from the graph (detach, or numbers taken out with to_vec) or left in \
    it (td_target must be detached). Build both losses from probs and values with tensor \
    operations only.";

/// A failure's problem, expected, got, detail and (hint, mistake id).
type Found = (Problem, String, String, String, (String, Option<String>));

/// A failure that is not a wrong value.
pub(super) fn problem(answer: &Answer) -> Found {
    let (problem, hint) = match answer {
        Answer::Error(m) => (Problem::Error(m.clone()), error_hint(m)),
        Answer::Panicked(m) => (Problem::Panicked(m.clone()), crate::grade::panic_hint(m)),
        Answer::TimedOut(s) => (
            Problem::TimedOut(*s),
            "Check that every loop ends; tensor operations on the whole batch need no loop \
             at all."
                .to_string(),
        ),
        Answer::Crashed(m) => (
            Problem::Crashed(m.clone()),
            "The program died on this input: unbounded recursion (stack overflow) or \
             std::process::exit are the usual causes."
                .to_string(),
        ),
        Answer::Reply(_) | Answer::NotRun => (Problem::Wrong, HINT.to_string()),
    };
    (
        problem,
        String::new(),
        String::new(),
        String::new(),
        (hint, None),
    )
}

/// A hint for an error the function returned.
pub(super) fn error_hint(message: &str) -> String {
    let hint = if message.contains("not a scalar") {
        "Each loss must be a single number: mean_all() averages every element into a scalar \
         (mean(0) leaves a shape [1])."
    } else if message.contains("shape mismatch") || message.contains("broadcast") {
        "The shapes do not line up: probs is (N, 2) and every other column (N, 1); \
         probs.gather(actions, 1) picks the action's probability as (N, 1), and the \
         operators +, -, * need equal shapes (or the broadcast_ versions)."
    } else if message.contains("dtype") {
        "Mixed dtypes: the tensors are f32 and candle does not convert implicitly; scalars \
         like 1.0 - eps go straight into clamp or affine, and Tensor::new(&[1.0], ..) makes \
         an f64 tensor."
    } else {
        "Your function returned an error on this input: read the message, then run the \
         candle operations on the input above one by one."
    };
    hint.to_string()
}

/// The input, for a failure: every column, cut short.
pub(super) fn show_inputs(inputs: &Inputs) -> Vec<(String, String)> {
    let pairs: Vec<[f32; 2]> = inputs
        .probs
        .chunks(2)
        .map(|p| [p[0], p[p.len() - 1]])
        .collect();
    let actions: Vec<usize> = inputs.actions.iter().map(|&a| a as usize).collect();
    vec![
        ("probs".into(), Arg::Pairs(pairs).show()),
        ("actions".into(), Arg::Usizes(actions).show()),
        (
            "old_log_probs".into(),
            Arg::F32s(inputs.old_log_probs.clone()).show(),
        ),
        (
            "advantage".into(),
            Arg::F32s(inputs.advantage.clone()).show(),
        ),
        ("values".into(), Arg::F32s(inputs.values.clone()).show()),
        (
            "td_target".into(),
            Arg::F32s(inputs.td_target.clone()).show(),
        ),
        ("eps".into(), format!("{:?}", inputs.eps)),
    ]
}

/// The training check: CartPole with the learner's losses in every epoch.
pub(super) fn training(
    learner: &mut dyn Learner,
    limit: Duration,
    diagnosed: Option<&'static Mistake>,
) -> CheckStatus {
    if learner.is_stopped() {
        return CheckStatus::NotRun("an earlier case stopped the program".into());
    }
    let mut failure: Option<Answer> = None;
    let result = {
        let mut answer = |inputs: &Inputs| match learner.ask(inputs, limit) {
            Answer::Reply(reply) => Ok(reply),
            Answer::NotRun => Err("the program had stopped".to_string()),
            other => {
                failure = Some(other);
                Err("the learner's function gave no losses".to_string())
            }
        };
        train(&mut answer, TRAIN_SEED, TRAIN_EPISODES)
    };
    let input = vec![
        ("seed".to_string(), TRAIN_SEED.to_string()),
        ("episodes".to_string(), TRAIN_EPISODES.to_string()),
    ];
    let expected = format!(
        "a mean of the last {TRAIN_WINDOW} returns of at least {LEARNS_AT} (the reference \
         solution: {REFERENCE_MEAN})"
    );
    let hint = diagnosed.map_or(
        "Your losses match the seed's on every input above, yet CartPole does not learn \
         with them: check that nothing in your function depends on anything but its \
         arguments.",
        |m| m.hint,
    );
    let failed = |problem, got: String, detail: String, hint: String| {
        CheckStatus::Failed(Box::new(Failure {
            problem,
            input: input.clone(),
            expected: expected.clone(),
            got,
            detail,
            hint,
        }))
    };
    match (result, failure) {
        (Ok(returns), _) => {
            let mean = mean_last(&returns, TRAIN_WINDOW);
            if mean >= LEARNS_AT {
                return CheckStatus::Passed;
            }
            let every: Vec<f64> = returns.iter().step_by(20).copied().collect();
            failed(
                Problem::Wrong,
                format!("a mean of {mean:.1}"),
                format!(
                    "CartPole did not learn: the returns every 20 episodes were {}",
                    Arg::F64s(every).show()
                ),
                hint.to_string(),
            )
        }
        (Err(_), Some(answer)) => {
            let (problem, _, _, _, (hint, _)) = self::problem(&answer);
            failed(problem, String::new(), String::new(), hint)
        }
        (Err(e), None) => failed(
            Problem::Wrong,
            e.to_string(),
            "training stopped".into(),
            hint.to_string(),
        ),
    }
}
