//! Which shard a run is, from the command line or from the scheduler that
//! started it.
//!
//! `--shard i/n` says it directly. Without it, a run started as one task of a
//! **Slurm job array** or one pod of a **Kubernetes Indexed Job** takes its
//! shard from the environment the scheduler gives it, so one script or one
//! manifest runs every shard (`docs/SCALE.md`):
//!
//! - Slurm: `SLURM_ARRAY_TASK_ID`, `SLURM_ARRAY_TASK_MIN` and
//!   `SLURM_ARRAY_TASK_COUNT` — shard `ID − MIN` of `COUNT`. The array must be
//!   one contiguous range with step 1 (`--array=0-7`, `--array=1-8`, with or
//!   without a `%` limit), or some shards would never run; an array with a step,
//!   or a list with gaps, is refused with the reason.
//! - Kubernetes: `JOB_COMPLETION_INDEX` (set by an Indexed Job) and
//!   `JOB_COMPLETIONS`, the Job's `completions`, which the manifest passes to
//!   the container (Kubernetes does not export the count itself).
//!
//! A variable that is present but malformed is an error naming it, never
//! silently a whole run: a shard that quietly ran everything would be counted
//! n times by `merge`.

/// A run's shard and where it came from (`--shard`, or the variables read).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Shard {
    /// `(index, count)`, `0 ≤ index < count`.
    pub shard: (u32, u32),
    /// Where it came from, for the run's output: `--shard` or the variables.
    pub from: String,
}

fn number(get: &impl Fn(&str) -> Option<String>, name: &str) -> Result<Option<u64>, String> {
    match get(name) {
        None => Ok(None),
        Some(v) => {
            v.trim().parse::<u64>().map(Some).map_err(|e| format!("{name}={v:?}: not a non-negative integer ({e})"))
        }
    }
}

fn checked(index: u64, count: u64, from: String) -> Result<Shard, String> {
    if count == 0 || index >= count {
        return Err(format!("{from} gives shard {index} of {count}: need 0 ≤ index < count"));
    }
    let (Ok(i), Ok(n)) = (u32::try_from(index), u32::try_from(count)) else {
        return Err(format!("{from} gives shard {index} of {count}: more than {} shards", u32::MAX));
    };
    Ok(Shard { shard: (i, n), from })
}

/// The shard given by a scheduler's environment, read through `get` (the
/// process environment in the command, a map in tests): `Ok(None)` when no
/// scheduler variable is set. Slurm's array variables are read first.
pub fn from_env(get: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>, String> {
    if let Some(id) = number(&get, "SLURM_ARRAY_TASK_ID")? {
        let need = |name: &str| -> Result<u64, String> {
            number(&get, name)?.ok_or_else(|| format!("SLURM_ARRAY_TASK_ID is set but {name} is not"))
        };
        let (min, count) = (need("SLURM_ARRAY_TASK_MIN")?, need("SLURM_ARRAY_TASK_COUNT")?);
        if let Some(step) = number(&get, "SLURM_ARRAY_TASK_STEP")?
            && step != 1
            && count > 1
        {
            return Err(format!(
                "SLURM_ARRAY_TASK_STEP={step}: the array's task ids must be one contiguous range (step 1), or the \
                 shards between them would never run"
            ));
        }
        if let Some(max) = number(&get, "SLURM_ARRAY_TASK_MAX")?
            && max.checked_sub(min).map(|d| d + 1) != Some(count)
        {
            return Err(format!(
                "SLURM_ARRAY_TASK_MIN={min}, SLURM_ARRAY_TASK_MAX={max} and SLURM_ARRAY_TASK_COUNT={count}: the \
                 array's task ids are not one contiguous range, so some shards would never run"
            ));
        }
        let index = id
            .checked_sub(min)
            .ok_or_else(|| format!("SLURM_ARRAY_TASK_ID={id} is below SLURM_ARRAY_TASK_MIN={min}"))?;
        let from = format!("SLURM_ARRAY_TASK_ID={id} (SLURM_ARRAY_TASK_MIN={min}, SLURM_ARRAY_TASK_COUNT={count})");
        return checked(index, count, from).map(Some);
    }
    if let Some(index) = number(&get, "JOB_COMPLETION_INDEX")? {
        let count = number(&get, "JOB_COMPLETIONS")?.ok_or(
            "JOB_COMPLETION_INDEX is set but JOB_COMPLETIONS is not: give the container the Job's completions count \
             (docs/SCALE.md), or pass --shard i/n",
        )?;
        let from = format!("JOB_COMPLETION_INDEX={index} (JOB_COMPLETIONS={count})");
        return checked(index, count, from).map(Some);
    }
    Ok(None)
}

/// The run's shard: `--shard` when given (it wins over the environment), else
/// the scheduler's, else none (the whole campaign).
pub fn resolve(flag: Option<(u32, u32)>, get: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>, String> {
    match flag {
        Some(shard) => Ok(Some(Shard { shard, from: "--shard".into() })),
        None => from_env(get),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env(vars: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> = vars.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
        move |k| map.get(k).cloned()
    }

    fn shard(vars: &[(&str, &str)]) -> Result<Option<(u32, u32)>, String> {
        from_env(env(vars)).map(|s| s.map(|s| s.shard))
    }

    #[test]
    fn no_scheduler_is_the_whole_campaign() {
        assert_eq!(shard(&[("HOME", "/root")]), Ok(None));
    }

    #[test]
    fn slurm_arrays_from_zero_and_from_one() {
        let zero = [("SLURM_ARRAY_TASK_ID", "3"), ("SLURM_ARRAY_TASK_MIN", "0"), ("SLURM_ARRAY_TASK_COUNT", "4")];
        assert_eq!(shard(&zero), Ok(Some((3, 4))));
        let one = [
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "8"),
            ("SLURM_ARRAY_TASK_STEP", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        assert_eq!(shard(&one), Ok(Some((0, 8))));
    }

    #[test]
    fn slurm_arrays_with_gaps_are_refused() {
        let stepped = [
            ("SLURM_ARRAY_TASK_ID", "2"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
            ("SLURM_ARRAY_TASK_COUNT", "4"),
        ];
        assert!(shard(&stepped).unwrap_err().contains("SLURM_ARRAY_TASK_STEP=2"));
        // --array=0,2,5: three tasks spanning six ids.
        let listed = [
            ("SLURM_ARRAY_TASK_ID", "5"),
            ("SLURM_ARRAY_TASK_MIN", "0"),
            ("SLURM_ARRAY_TASK_MAX", "5"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        assert!(shard(&listed).unwrap_err().contains("not one contiguous range"));
        let missing = [("SLURM_ARRAY_TASK_ID", "2"), ("SLURM_ARRAY_TASK_MIN", "0")];
        assert!(shard(&missing).unwrap_err().contains("SLURM_ARRAY_TASK_COUNT is not"));
        let garbled = [("SLURM_ARRAY_TASK_ID", "two")];
        assert!(shard(&garbled).unwrap_err().contains("SLURM_ARRAY_TASK_ID=\"two\""));
    }

    #[test]
    fn kubernetes_indexed_jobs() {
        assert_eq!(shard(&[("JOB_COMPLETION_INDEX", "0"), ("JOB_COMPLETIONS", "4")]), Ok(Some((0, 4))));
        assert!(shard(&[("JOB_COMPLETION_INDEX", "0")]).unwrap_err().contains("JOB_COMPLETIONS is not"));
        assert!(shard(&[("JOB_COMPLETION_INDEX", "4"), ("JOB_COMPLETIONS", "4")]).unwrap_err().contains("0 ≤ index"));
    }

    #[test]
    fn the_flag_wins_and_says_so() {
        let k8s = env(&[("JOB_COMPLETION_INDEX", "1"), ("JOB_COMPLETIONS", "4")]);
        let s = resolve(Some((2, 3)), k8s).unwrap().unwrap();
        assert_eq!((s.shard, s.from.as_str()), ((2, 3), "--shard"));
        let s = resolve(None, env(&[("JOB_COMPLETION_INDEX", "1"), ("JOB_COMPLETIONS", "4")])).unwrap().unwrap();
        assert_eq!(s.shard, (1, 4));
        assert!(s.from.contains("JOB_COMPLETION_INDEX=1"), "{}", s.from);
    }
}
