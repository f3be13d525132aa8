//! The kinds of connector: which variables each has, which is the
//! potential (equal across a connection) and which the flow (summing to
//! zero), and which kinds connect.

/// A kind of connector, declared in a component with `let p = pin();`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ConnectorKind {
    /// Electrical: potential `v` (V), current `i` (A).
    Pin,
    /// Rotational: angle `phi` (rad), torque `tau` (N m).
    Flange,
    /// Translational: position `s` (m), force `f` (N).
    TranslationalFlange,
    /// Thermal: temperature `t` (K), heat flow `q` (W).
    HeatPort,
    /// A causal signal the component reads.
    RealInput,
    /// A causal signal the component sets.
    RealOutput,
}

impl ConnectorKind {
    /// Every kind, in the order the guide lists them.
    pub const ALL: [ConnectorKind; 6] = [
        ConnectorKind::Pin,
        ConnectorKind::Flange,
        ConnectorKind::TranslationalFlange,
        ConnectorKind::HeatPort,
        ConnectorKind::RealInput,
        ConnectorKind::RealOutput,
    ];

    /// The function that declares one.
    pub fn name(self) -> &'static str {
        match self {
            ConnectorKind::Pin => "pin",
            ConnectorKind::Flange => "flange",
            ConnectorKind::TranslationalFlange => "translational_flange",
            ConnectorKind::HeatPort => "heat_port",
            ConnectorKind::RealInput => "real_input",
            ConnectorKind::RealOutput => "real_output",
        }
    }

    /// The kind `name()` declares.
    pub fn from_name(name: &str) -> Option<ConnectorKind> {
        ConnectorKind::ALL.into_iter().find(|k| k.name() == name)
    }

    /// The potential variable's name; `None` for a signal, which is a
    /// value itself.
    pub fn potential(self) -> Option<&'static str> {
        match self {
            ConnectorKind::Pin => Some("v"),
            ConnectorKind::Flange => Some("phi"),
            ConnectorKind::TranslationalFlange => Some("s"),
            ConnectorKind::HeatPort => Some("t"),
            ConnectorKind::RealInput | ConnectorKind::RealOutput => None,
        }
    }

    /// The flow variable's name; `None` for a signal.
    pub fn flow(self) -> Option<&'static str> {
        match self {
            ConnectorKind::Pin => Some("i"),
            ConnectorKind::Flange => Some("tau"),
            ConnectorKind::TranslationalFlange => Some("f"),
            ConnectorKind::HeatPort => Some("q"),
            ConnectorKind::RealInput | ConnectorKind::RealOutput => None,
        }
    }

    /// Whether a connector of this kind may join one of `other`: the same
    /// physical kind, or signals (an output feeding inputs).
    pub fn connects_to(self, other: ConnectorKind) -> bool {
        self == other || (self.is_signal() && other.is_signal())
    }

    /// A signal, input or output.
    pub fn is_signal(self) -> bool {
        matches!(self, ConnectorKind::RealInput | ConnectorKind::RealOutput)
    }

    /// What it is, for messages.
    pub fn describe(self) -> &'static str {
        match self {
            ConnectorKind::Pin => "an electrical pin",
            ConnectorKind::Flange => "a rotational flange",
            ConnectorKind::TranslationalFlange => "a translational flange",
            ConnectorKind::HeatPort => "a heat port",
            ConnectorKind::RealInput => "a signal input",
            ConnectorKind::RealOutput => "a signal output",
        }
    }
}
