//! The folders that are never an output destination: the system's own trees, and the shared
//! folders whose top level belongs to everyone (a sub-folder of them may be an output folder).
//! The one list, with the reason each is refused; paths are compared after canonicalisation, so
//! a symbolic link or `..` leads to the same verdict as the folder itself.

use std::path::Path;

/// Trees refused whole: the folder and everything below it.
const TREES: &[(&str, &str)] = &[
    ("/etc", "the system's configuration"),
    ("/usr", "installed software"),
    ("/bin", "system programs"),
    ("/sbin", "system programs"),
    ("/lib", "system libraries"),
    ("/lib32", "system libraries"),
    ("/lib64", "system libraries"),
    ("/libx32", "system libraries"),
    ("/boot", "the boot loader and kernels"),
    ("/dev", "device files"),
    ("/proc", "the kernel's view of processes"),
    ("/sys", "the kernel's view of devices"),
    ("/var/lib", "system services' state"),
    ("/var/log", "system logs"),
    ("/var/spool", "system queues"),
    ("/var/cache", "system caches"),
    ("/System", "the macOS system"),
    ("/Library", "macOS system libraries"),
];

/// Folders refused themselves; a folder below them may be an output folder.
const TOPS: &[(&str, &str)] = &[
    ("/", "the root of the file system"),
    ("/var", "variable system data"),
    ("/home", "every user's home folder"),
    ("/Users", "every user's home folder"),
    ("/root", "the administrator's home folder"),
    ("/tmp", "shared by every user"),
    ("/var/tmp", "shared by every user"),
    ("/opt", "installed software"),
    ("/srv", "served data"),
    ("/mnt", "mount points"),
    ("/media", "mount points"),
    ("/run", "the running system's state"),
    ("/private", "the macOS system"),
];

/// Why the canonical folder `dir` may not be an output folder, or `None` when it may. `home` is
/// the user's canonical home folder, refused itself.
pub(super) fn refusal(dir: &Path, home: Option<&Path>) -> Option<String> {
    if let Some(why) = tree_refusal(dir) {
        return Some(why);
    }
    if let Some((_, why)) = TOPS.iter().find(|(top, _)| dir == Path::new(top)) {
        return Some(format!("{} is {why}: choose a folder inside it", dir.display()));
    }
    (home == Some(dir)).then(|| format!("{} is your home folder: choose a folder inside it", dir.display()))
}

/// Why no file may be written into the canonical folder `dir` (a system tree, or `/`), or
/// `None`: a single output file (`verify --junit`) may go into a shared folder such as `/tmp`.
pub(super) fn file_refusal(dir: &Path) -> Option<String> {
    tree_refusal(dir).or_else(|| {
        (dir == Path::new("/")).then(|| "/ is the root of the file system: choose a folder inside it".into())
    })
}

/// Why `dir` lies in a system tree, or `None`.
fn tree_refusal(dir: &Path) -> Option<String> {
    let (tree, why) = TREES.iter().find(|(tree, _)| dir.starts_with(tree))?;
    Some(format!(
        "{tree} holds {why}: neither it nor a folder in it is an output folder"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn system_trees_and_shared_tops_are_refused_but_folders_below_the_tops_are_not() {
        let home = Path::new("/home/someone");
        let refused = |d: &str| refusal(Path::new(d), Some(home)).is_some();
        for dir in [
            "/",
            "/etc",
            "/etc/ssl",
            "/usr/local/x",
            "/lib64",
            "/proc/1",
            "/var",
            "/tmp",
        ] {
            assert!(refused(dir), "{dir} accepted");
        }
        assert!(refused("/home/someone"), "the home folder accepted");
        assert!(file_refusal(Path::new("/etc/ssl")).is_some() && file_refusal(Path::new("/")).is_some());
        assert!(
            file_refusal(Path::new("/tmp")).is_none(),
            "a JUnit file in /tmp refused"
        );
        for dir in [
            "/tmp/out",
            "/var/tmp/x",
            "/home/someone/out",
            "/etcetera",
            "/srv/data/out",
        ] {
            assert!(!refused(dir), "{dir} refused");
        }
    }
}
