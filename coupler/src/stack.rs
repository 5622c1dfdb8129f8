//! The running participants of a case: their processes, their links, the handshake, and
//! every message in and out (each one recorded, but for progress reports: [`liveness`]).

mod liveness;

use crate::error::CouplerError;
use crate::launch::{behind_launcher, log_tail, Children};
use liveness::{no_progress, progress_interval, LastReport};
use schemas::link::{Link, LinkError, Side};
use schemas::message::{FromParticipant, Geometry, InterfaceDecl, Role, ToParticipant, PROTOCOL_VERSION};
use schemas::recording::{Message, Recorder};
use schemas::signals;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// How long a participant may take to start and say hello.
const START_TIMEOUT: Duration = Duration::from_secs(60);

/// What the coupler knows of one participant after the handshake.
pub struct Session {
    pub name: String,
    pub role: Role,
    pub interface: InterfaceDecl,
    pub geometry: Option<Geometry>,
    pub log: PathBuf,
    link: Link,
}

/// A participant to start: name, role, executable and arguments, and the launcher that starts
/// it on MPI ranks (empty: one process; see [`crate::launch::launcher_for`]).
pub struct Launch {
    pub name: String,
    pub role: Role,
    pub exe: PathBuf,
    pub args: Vec<String>,
    pub launcher: Vec<String>,
}

/// The participants of a run, in serial order.
pub struct Stack {
    pub sessions: Vec<Session>,
    children: Children,
    recorder: Option<Recorder>,
    started: Instant,
    /// Longest wall time a participant may go without answering or reporting progress.
    timeout: Duration,
}

impl Stack {
    /// Starts every participant, opens their links and shakes hands (protocol version, role,
    /// case hash); each is asked for progress reports at [`progress_interval`] of `timeout`, the
    /// longest wall time it may go without answering or reporting. Returns the stack and each
    /// participant's initial outputs. A run resumed from a checkpoint taken `resumed` wall seconds
    /// into the run appends to the logs, keeps its wall clock going from there, and does not record
    /// the handshake (the recording already holds the first run's). When a participant cannot be
    /// started or refuses the handshake, the others are stopped and the recording ends with why
    /// ([`Stack::abort`]).
    pub fn launch(
        launches: Vec<Launch>,
        run_id: &str,
        case_hash: u64,
        out: &std::path::Path,
        recorder: Option<Recorder>,
        timeout: Duration,
        resumed: Option<f64>,
    ) -> Result<(Stack, Vec<schemas::message::Fields>), CouplerError> {
        let now = Instant::now();
        let mut stack = Stack {
            sessions: Vec::new(),
            children: Children::default(),
            recorder: None,
            started: resumed
                .and_then(|wall| now.checked_sub(Duration::from_secs_f64(wall.max(0.0))))
                .unwrap_or(now),
            timeout,
        };
        // a resumed run's handshake is not recorded: the recorder joins after it
        let held = match resumed {
            Some(_) => recorder,
            None => {
                stack.recorder = recorder;
                None
            }
        };
        let initial = match stack.start(&launches, run_id, case_hash, out, resumed.is_some()) {
            Ok(initial) => initial,
            Err(e) => {
                if held.is_some() {
                    stack.recorder = held;
                }
                stack.abort(&e);
                return Err(e);
            }
        };
        if held.is_some() {
            stack.recorder = held;
        }
        Ok((stack, initial))
    }

    /// Starts every participant, opens its link and shakes hands; returns their initial outputs.
    fn start(
        &mut self,
        launches: &[Launch],
        run_id: &str,
        case_hash: u64,
        out: &std::path::Path,
        append_logs: bool,
    ) -> Result<Vec<schemas::message::Fields>, CouplerError> {
        let interval = progress_interval(self.timeout).as_secs_f64().to_string();
        for l in launches {
            let log = out.join(format!("{}.log", l.name));
            let mut args = l.args.clone();
            args.extend(["--progress-interval".to_string(), interval.clone()]);
            let (program, args) = behind_launcher(&l.launcher, &l.exe, &args);
            let pid = self.children.spawn(&l.name, &program, &args, &log, append_logs)?;
            match l.launcher.is_empty() {
                true => crate::say!("started {} ({}, pid {pid})", l.name, l.exe.display()),
                false => crate::say!(
                    "started {} ({} {}, rank 0 talking to the coupler, pid {pid})",
                    l.name,
                    l.launcher.join(" "),
                    l.exe.display()
                ),
            }
            let link =
                Link::open(run_id, &l.name, Side::Coupler).map_err(|e| link_error(&l.name, None, e))?;
            self.sessions.push(Session {
                name: l.name.clone(),
                role: l.role,
                interface: InterfaceDecl::default(),
                geometry: None,
                log,
                link,
            });
        }
        let mut initial = Vec::new();
        for i in 0..self.sessions.len() {
            initial.push(self.handshake(i, run_id, case_hash)?);
        }
        Ok(initial)
    }

    fn handshake(
        &mut self,
        i: usize,
        run_id: &str,
        case_hash: u64,
    ) -> Result<schemas::message::Fields, CouplerError> {
        let name = self.sessions[i].name.clone();
        let expected_role = self.sessions[i].role;
        let deadline = Instant::now() + START_TIMEOUT;
        let late = format!(
            "did not connect and say Hello within {} s of its start",
            START_TIMEOUT.as_secs()
        );
        self.wait(i, None, late.clone(), |link, alive| {
            link.wait_for_peer(deadline, alive)
        })?;
        let hello = self.wait(i, None, late, |link, alive| {
            link.recv::<FromParticipant>(Some(deadline), alive)
        })?;
        let hello = match self.take(i, hello)? {
            FromParticipant::Hello(h) => h,
            other => return Err(self.protocol_error(i, None, "Hello", &other)),
        };
        let refusal = if hello.protocol != PROTOCOL_VERSION {
            Some(format!(
                "it speaks protocol version {}, this coupler speaks version {PROTOCOL_VERSION}; rebuild it against \
                 this workspace's schemas",
                hello.protocol
            ))
        } else if hello.name != name {
            Some(format!("it says its name is `{}`", hello.name))
        } else if hello.role != expected_role {
            Some(format!(
                "it is a {:?} solver, the case declares a {:?} participant",
                hello.role, expected_role
            ))
        } else if hello.case_hash != case_hash {
            Some(format!(
                "it loaded a different case file (hash {:016x}, the coupler's is {case_hash:016x})",
                hello.case_hash
            ))
        } else {
            None
        };
        if let Some(reason) = refusal {
            self.send(
                i,
                ToParticipant::Refused {
                    reason: reason.clone(),
                },
                None,
            )?;
            return Err(CouplerError::Participant {
                name,
                window: None,
                message: format!("refused at the handshake: {reason}"),
            });
        }
        self.sessions[i].interface = hello.interface;
        self.send(
            i,
            ToParticipant::Welcome {
                run_id: run_id.to_string(),
            },
            None,
        )?;
        match self.recv(i, None)? {
            FromParticipant::Initial { outputs, geometry } => {
                self.sessions[i].geometry = geometry;
                Ok(outputs)
            }
            other => Err(self.protocol_error(i, None, "Initial", &other)),
        }
    }

    /// Sends one message to participant `i` and records it.
    pub fn send(&mut self, i: usize, msg: ToParticipant, window: Option<u64>) -> Result<(), CouplerError> {
        let name = self.sessions[i].name.clone();
        self.sessions[i]
            .link
            .send(&msg)
            .map_err(|e| link_error(&name, window, e))?;
        self.record(&name, Message::To(msg))
    }

    /// Asks participant `i` to write its checkpoint of window `window` to `path` and waits for it
    /// to say it did. Neither message is recorded (see [`ToParticipant::WriteCheckpoint`]).
    pub fn write_checkpoint(
        &mut self,
        i: usize,
        window: u64,
        path: &std::path::Path,
    ) -> Result<u64, CouplerError> {
        let name = self.sessions[i].name.clone();
        let msg = ToParticipant::WriteCheckpoint {
            window,
            path: path.display().to_string(),
        };
        self.sessions[i]
            .link
            .send(&msg)
            .map_err(|e| link_error(&name, Some(window), e))?;
        match self.answer(i, Some(window))? {
            FromParticipant::CheckpointWritten { window: w, bytes } if w == window => Ok(bytes),
            FromParticipant::Failed { diagnostic, .. } => Err(CouplerError::Participant {
                name,
                window: Some(window),
                message: format!("could not write its checkpoint: {diagnostic}"),
            }),
            other => Err(self.protocol_error(i, Some(window), "CheckpointWritten", &other)),
        }
    }

    /// Seconds of wall time since the run started (a resumed run: since the first run started,
    /// less the time it was down).
    pub fn wall_seconds(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Waits (idle) for participant `i`'s answer ([`Stack::answer`]) and records it.
    pub fn recv(&mut self, i: usize, window: Option<u64>) -> Result<FromParticipant, CouplerError> {
        let msg = self.answer(i, window)?;
        self.take(i, msg)
    }

    /// Waits (idle) for participant `i`'s answer, taking its progress reports on the way (not
    /// recorded): it is taken as hung when neither comes for the case's timeout, however long the
    /// whole answer takes.
    fn answer(&mut self, i: usize, window: Option<u64>) -> Result<FromParticipant, CouplerError> {
        let mut last: Option<LastReport> = None;
        loop {
            let deadline = Instant::now() + self.timeout;
            let late = no_progress(self.timeout, last.as_ref());
            match self.wait(i, window, late, |link, alive| {
                link.recv::<FromParticipant>(Some(deadline), alive)
            })? {
                FromParticipant::Progress { header, steps } => {
                    last = Some(LastReport {
                        steps,
                        time: header.time,
                    })
                }
                answer => return Ok(answer),
            }
        }
    }

    /// Records a message of participant `i`; a `Failed` one becomes the participant's error.
    fn take(&mut self, i: usize, msg: FromParticipant) -> Result<FromParticipant, CouplerError> {
        let name = self.sessions[i].name.clone();
        self.record(&name, Message::From(msg.clone()))?;
        if let FromParticipant::Failed { header, diagnostic } = &msg {
            return Err(CouplerError::Participant {
                name,
                window: Some(header.window),
                message: format!("the solver stopped at t = {:.6} s: {diagnostic}", header.time),
            });
        }
        Ok(msg)
    }

    /// Runs a blocking link call for participant `i` while watching every process and Ctrl-C; when
    /// the call times out, the participant's error says `late`.
    fn wait<T>(
        &mut self,
        i: usize,
        window: Option<u64>,
        late: String,
        call: impl FnOnce(&Link, &mut dyn FnMut() -> Result<(), String>) -> Result<T, LinkError>,
    ) -> Result<T, CouplerError> {
        let mut cause: Option<CouplerError> = None;
        let children = &mut self.children;
        let sessions = &self.sessions;
        let mut alive = || {
            if signals::interrupted() {
                cause = Some(CouplerError::Interrupted { window });
                return Err("interrupted".to_string());
            }
            children.check().map_err(|(name, what)| {
                let log = sessions
                    .iter()
                    .find(|s| s.name == name)
                    .map(|s| s.log.clone())
                    .unwrap_or_default();
                let tail = log_tail(&log, 5);
                let message = if tail.is_empty() {
                    what.clone()
                } else {
                    format!("{what}; the end of {}:\n{tail}", log.display())
                };
                cause = Some(CouplerError::Participant {
                    name,
                    window,
                    message,
                });
                what
            })
        };
        let result = call(&sessions[i].link, &mut alive);
        match (result, cause) {
            (Ok(v), _) => Ok(v),
            (Err(_), Some(c)) => Err(c),
            (Err(LinkError::Timeout), None) => Err(CouplerError::Participant {
                name: self.sessions[i].name.clone(),
                window,
                message: late,
            }),
            (Err(e), None) => Err(link_error(&self.sessions[i].name, window, e)),
        }
    }

    fn record(&mut self, name: &str, msg: Message) -> Result<(), CouplerError> {
        let wall = self.started.elapsed().as_secs_f64();
        match &mut self.recorder {
            Some(r) => r.record(name, wall, msg).map_err(|e| {
                CouplerError::Io(format!("cannot write the recording {}: {e}", r.path().display()))
            }),
            None => Ok(()),
        }
    }

    fn protocol_error(
        &self,
        i: usize,
        window: Option<u64>,
        expected: &str,
        got: &FromParticipant,
    ) -> CouplerError {
        CouplerError::Participant {
            name: self.sessions[i].name.clone(),
            window,
            message: format!("protocol error: expected {expected}, got {}", variant(got)),
        }
    }

    /// Ends the run: `Finish` to everyone, their `Finished`, and their exit; then the warnings in their
    /// logs are passed on to the user. The recording is closed with its end record: `end`, the
    /// windows the run ran (from its start, a resumed run's included) and the simulated time it
    /// reached [s] — or, when a participant fails now, why ([`Stack::abort`]). `end` is `None` where
    /// nothing is recorded (a replay).
    pub fn finish(mut self, end: Option<(u64, f64)>) -> Result<(), CouplerError> {
        if let Err(e) = self
            .finish_participants()
            .map_err(CouplerError::after_last_window)
        {
            self.abort(&e);
            return Err(e);
        }
        let wall = self.started.elapsed().as_secs_f64();
        match (self.recorder.take(), end) {
            (Some(r), Some((windows, time))) => {
                let path = r.path().to_path_buf();
                r.end(wall, windows, time).map_err(|e| {
                    CouplerError::Io(format!(
                        "cannot write the end of the recording {}: {e}",
                        path.display()
                    ))
                })
            }
            _ => Ok(()),
        }
    }

    /// The steps of [`Stack::finish`]; its participants' errors carry no window.
    fn finish_participants(&mut self) -> Result<(), CouplerError> {
        for i in 0..self.sessions.len() {
            self.send(i, ToParticipant::Finish, None)?;
            match self.recv(i, None)? {
                FromParticipant::Finished => self.children.finished(&self.sessions[i].name),
                other => return Err(self.protocol_error(i, None, "Finished", &other)),
            }
        }
        for (name, status) in self.children.wait_all(Duration::from_secs(10)) {
            match status {
                Some(s) if s.success() => {}
                Some(s) => {
                    return Err(CouplerError::Participant {
                        name,
                        window: None,
                        message: format!("exited with {} after the run", crate::launch::describe(s)),
                    })
                }
                None => {
                    return Err(CouplerError::Participant {
                        name,
                        window: None,
                        message: "did not exit within 10 s after Finish".into(),
                    })
                }
            }
        }
        for s in &self.sessions {
            for warning in crate::launch::log_warnings(&s.log) {
                crate::say!("warning from {}: {warning}", s.name);
            }
        }
        Ok(())
    }

    /// Stops every participant now (after an error or Ctrl-C), and ends the recording with why the
    /// run ended ([`Message::Died`]: the window, the participant at fault if any, and `why` as the
    /// user is told it). Nothing is recorded after it.
    pub fn abort(&mut self, why: &CouplerError) {
        if let Some(r) = self.recorder.take() {
            let participant = match why {
                CouplerError::Participant { name, .. } | CouplerError::AfterLastWindow { name, .. } => {
                    Some(name.clone())
                }
                _ => None,
            };
            let wall = self.started.elapsed().as_secs_f64();
            // The run already failed with `why`; a recording that cannot take its last frame adds
            // nothing the user must act on first.
            let _ = r.died(wall, why.window(), participant, why.to_string());
        }
        self.children.stop_all(Duration::from_secs(1));
    }
}

/// The name of a participant message's kind, for error messages.
pub fn variant(m: &FromParticipant) -> &'static str {
    match m {
        FromParticipant::Hello(_) => "Hello",
        FromParticipant::Initial { .. } => "Initial",
        FromParticipant::Advanced { .. } => "Advanced",
        FromParticipant::Failed { .. } => "Failed",
        FromParticipant::Finished => "Finished",
        FromParticipant::CheckpointWritten { .. } => "CheckpointWritten",
        FromParticipant::Progress { .. } => "Progress",
    }
}

fn link_error(name: &str, window: Option<u64>, e: LinkError) -> CouplerError {
    CouplerError::Participant {
        name: name.to_string(),
        window,
        message: format!("link: {e}"),
    }
}
