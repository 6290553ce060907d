//! The `sherd` command-line tool: the contract others script against
//! (`../shared/design.md`, "The command-line tool").

fn main() {
    eprintln!("sherd: no sub-command yet");
    std::process::exit(2);
}
