//! The exponential scheme's set-ups kept for the next run of the same loop.
//!
//! A ledger row runs one loop several times: the explicit FTDO's run, its initial-layer run at
//! the same step (the same e^{Ah} and Gramians), the statistics runs from nudged starts and at
//! dt/2 (the same A, so the same eigendecomposition). Each set-up is O(N³) — about a second at
//! 288 unknowns — while a step is O(N²) or O(N). The set-ups depend only on the inputs that make
//! up their key (the modal basis, the loop's coefficients and, for the dense transition, the
//! step), and they are deterministic, so a reused set-up is the one a fresh computation would
//! give, bit for bit (`tests::a_kept_setup_gives_the_fresh_runs_bits`; the key covers every input of
//! [`super::closed_loop::closed_loop`] and the probe rows, `tests::the_key_sees_every_input`).
//!
//! Bounded: each memo keeps its [`CAPACITY`] most recent set-ups (the oldest leaves first), so
//! the memory held between runs is at most that many of the largest loop's set-ups (at the
//! modal basis's limit of 3 072 unknowns, 6 149 states: two 6 149² matrices, 0.6 GB, for an
//! eigendecomposition; a run of that size is refused by the work estimate long before).

use std::sync::{Arc, Mutex};

use super::closed_loop::LoopCoefficients;
use super::ModalBasis;

/// Set-ups kept per memo: a row's run and its layer run, or its statistics runs, follow each
/// other; the ledger's parallel rows interleave at most two loops.
pub(crate) const CAPACITY: usize = 2;

/// The exact inputs a set-up is a function of, as bits (−0.0 and 0.0 differ, as they may in
/// the set-up).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Key(Vec<u64>);

impl Key {
    /// The loop on `basis` with coefficients `co`, and the step `h` (s) where the set-up
    /// depends on it (`None` for the eigendecomposition, which does not).
    pub(crate) fn of(basis: &ModalBasis, co: &LoopCoefficients, h: Option<f64>) -> Key {
        let LoopCoefficients { gain, a, b, xi, stiff, sign } = *co;
        let head = [basis.len() as f64, h.unwrap_or(f64::NAN), a, b, xi];
        let parts: [&[f64]; 9] = [
            &head,
            &gain,
            &stiff,
            &sign,
            &basis.omega2,
            &basis.tip[0],
            &basis.tip[1],
            &basis.load,
            &[basis.tip[0].len() as f64, basis.load.len() as f64],
        ];
        Key(parts.iter().flat_map(|p| p.iter().map(|x| x.to_bits())).collect())
    }
}

/// One kept set-up: empty while it is being made (or after making it failed).
type Slot<T> = Arc<Mutex<Option<Arc<T>>>>;

/// A few set-ups of one kind under keys `K` ([`Key`] unless named), most recent last.
#[derive(Debug)]
pub(crate) struct Memo<T, K = Key> {
    slots: Mutex<Vec<(K, Slot<T>)>>,
    /// Set-ups kept ([`CAPACITY`] unless [`Memo::keeping`] says otherwise).
    capacity: usize,
}

impl<T, K: PartialEq + Clone> Memo<T, K> {
    /// An empty memo.
    pub(crate) const fn new() -> Memo<T, K> {
        Memo::keeping(CAPACITY)
    }

    /// An empty memo that keeps `capacity` set-ups.
    pub(crate) const fn keeping(capacity: usize) -> Memo<T, K> {
        Memo { slots: Mutex::new(Vec::new()), capacity }
    }

    /// The set-up for `key`: the kept one, or `make()`'s (kept unless it failed). A run that
    /// asks for a set-up another thread is making waits for it (the ledger's statistics runs
    /// start together) instead of making it again; set-ups of other keys are made meanwhile.
    pub(crate) fn get_or_try<E>(&self, key: K, make: impl FnOnce() -> Result<T, E>) -> Result<Arc<T>, E> {
        let slot = self.slot(&key);
        let mut held = slot.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some(kept) = &*held {
            return Ok(Arc::clone(kept));
        }
        let made = Arc::new(make()?);
        *held = Some(Arc::clone(&made));
        Ok(made)
    }

    /// The slot of `key`, a new empty one (the oldest leaving beyond the capacity) where none is kept.
    fn slot(&self, key: &K) -> Slot<T> {
        let mut slots = self.slots.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
        if let Some((_, slot)) = slots.iter().find(|(k, _)| k == key) {
            return Arc::clone(slot);
        }
        let slot: Slot<T> = Arc::new(Mutex::new(None));
        slots.push((key.clone(), Arc::clone(&slot)));
        if slots.len() > self.capacity {
            slots.remove(0);
        }
        slot
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn key(x: u64) -> Key {
        Key(vec![x])
    }

    #[test]
    fn keeps_the_most_recent_and_computes_the_rest() {
        let memo = Memo::<u64>::new();
        let calls = std::cell::Cell::new(0);
        let get = |x: u64| {
            *memo
                .get_or_try::<()>(key(x), || {
                    calls.set(calls.get() + 1);
                    Ok(10 * x)
                })
                .unwrap()
        };
        assert_eq!((get(1), get(1), get(2), get(1)), (10, 10, 20, 10));
        assert_eq!(calls.get(), 2, "the repeated 1s were kept");
        assert_eq!(get(3), 30); // keeps 2 and 3: 1 was put in first
        assert_eq!(calls.get(), 3);
        assert_eq!((get(2), get(3)), (20, 30));
        assert_eq!(calls.get(), 3, "2 and 3 are kept");
        assert_eq!(get(1), 10);
        assert_eq!(calls.get(), 4, "1 had left: computed again");
    }

    #[test]
    fn a_failed_setup_is_not_kept() {
        let memo = Memo::<u64>::new();
        assert!(memo.get_or_try(key(7), || Err("refused")).is_err());
        assert_eq!(*memo.get_or_try::<()>(key(7), || Ok(70)).unwrap(), 70);
    }

    /// Threads asking for one set-up together make it once (the rest wait for it).
    #[test]
    fn a_setup_asked_for_together_is_made_once() {
        use std::sync::atomic::{AtomicUsize, Ordering};
        let memo = Memo::<u64>::new();
        let calls = AtomicUsize::new(0);
        let start = std::sync::Barrier::new(4);
        std::thread::scope(|s| {
            for _ in 0..4 {
                s.spawn(|| {
                    start.wait();
                    let got = memo.get_or_try::<()>(key(5), || {
                        calls.fetch_add(1, Ordering::SeqCst);
                        std::thread::sleep(std::time::Duration::from_millis(50));
                        Ok(50)
                    });
                    assert_eq!(*got.unwrap(), 50);
                });
            }
        });
        assert_eq!(calls.load(Ordering::SeqCst), 1);
    }

    fn paper_loop(sets: &[&str]) -> (wingcheck_model::Config, ModalBasis) {
        let over: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let cfg = wingcheck_model::apply_overrides(&wingcheck_model::Config::paper(), &over).unwrap();
        let basis = ModalBasis::new(&cfg).unwrap();
        (cfg, basis)
    }

    /// Every coefficient and every entry of the basis the loop's matrix and the probe rows read
    /// changes the key (one at a time, by one unit in the last place).
    #[test]
    fn the_key_sees_every_input() {
        let (_, basis) = paper_loop(&[]);
        let co = LoopCoefficients { gain: [1.5, 0.5], a: 1.0, b: 2.0, xi: 0.01, stiff: [5.0, 6.0], sign: [1.0, -1.0] };
        let base = Key::of(&basis, &co, Some(1e-3));
        let nudge = |x: &mut f64| *x = f64::from_bits(x.to_bits() + 1);
        let mut seen = 0;
        let mut differs = |key: Key| {
            assert_ne!(key, base);
            seen += 1;
        };
        differs(Key::of(&basis, &co, Some(1e-3 * (1.0 + f64::EPSILON))));
        differs(Key::of(&basis, &co, None));
        for field in 0..9 {
            let mut c = co;
            let LoopCoefficients { gain: [g0, g1], a, b, xi, stiff: [s0, s1], sign: [z0, z1] } = &mut c;
            nudge([g0, g1, a, b, xi, s0, s1, z0, z1].into_iter().nth(field).unwrap());
            differs(Key::of(&basis, &c, Some(1e-3)));
        }
        let n = basis.len();
        for i in [0, n / 2, n - 1] {
            for which in 0..4 {
                let (_, mut b) = paper_loop(&[]);
                match which {
                    0 => nudge(&mut b.omega2[i]),
                    1 => nudge(&mut b.tip[0][i]),
                    2 => nudge(&mut b.tip[1][i]),
                    _ => nudge(&mut b.load[i]),
                }
                differs(Key::of(&b, &co, Some(1e-3)));
            }
        }
        assert_eq!(seen, 2 + 9 + 12);
    }

    /// Runs of three loops in an order that keeps, evicts and re-makes their set-ups (dense and
    /// eigenbasis forms) give each loop's first run's bits, and different loops differ.
    #[test]
    fn a_kept_setup_gives_the_fresh_runs_bits() {
        let run = |sets: &[&str], eigenbasis: Option<f64>| {
            let mut over = vec!["discretisation.stepper=exponential", "horizon.t_end=0.2"];
            over.extend_from_slice(sets);
            let (cfg, _) = paper_loop(&over);
            let opts = crate::RunOptions { eigenbasis, ..Default::default() };
            let out = crate::simulate_base(&cfg, opts).unwrap();
            out.series.q_tip.iter().chain(&out.series.tau1).map(|x| x.to_bits()).collect::<Vec<u64>>()
        };
        let loops: [&[&str]; 3] = [&[], &["control.b=100"], &["wing.xi=0.02"]];
        for eigenbasis in [None, Some(1e-3)] {
            let first: Vec<Vec<u64>> = loops.iter().map(|l| run(l, eigenbasis)).collect();
            assert!(first[0] != first[1] && first[0] != first[2] && first[1] != first[2]);
            for i in [0, 0, 1, 2, 0, 2, 1, 1] {
                assert!(run(loops[i], eigenbasis) == first[i], "loop {i}, eigenbasis {eigenbasis:?}");
            }
        }
    }
}
