function merlin_case(merlin, name, out)
% Run one of MERLIN's published Miura-ori examples (Liu and Paulino 2017) with MERLIN's own
% functions, and save the model it assembled and its load path for curvefold to compare.
%   merlin: the folder of MERLIN's code; name: "bending", "folding" or "bistable"; out: a
%   .mat file.
addpath(merlin);
more off;
limits = [0.1, 360 - 0.1];  % the springs' linear range, deg (MERLIN's EnhancedLinear)
if strcmp(name, 'bending')
  % MIURA BENDING: 5 x 5 cells, a = b = 2, 60 deg panels at 54.7356 deg
  [Node, Panel, ~] = ConfigMiura(5, 5, 60, 2, 2, 54.7356);
  MaxIcr = 98; blam = 0.03; Kf = 1e-1; Kb = Kf*10; C0 = 1e4; Abar = 1e-1;
  Supp = [56, 1, 0, 0; 57, 1, 1, 1; 65, 1, 0, 1];
  Load = [56, 0, 0, -1; 66, 0, 0, -1];
  control = 3*56;
elseif strcmp(name, 'folding')
  % MIURA FOLDING: 5 x 5 cells at 15 deg, pulled along -x at its right edge
  [Node, Panel, ~] = ConfigMiura(5, 5, 60, 2, 2, 15);
  MaxIcr = 60; blam = 0.5; Kf = 1e-1; Kb = Kf*1e5; C0 = 1e6; Abar = 1e-1;
  n = 11;
  leftx = 1:n; leftz = 1:2:n; rightz = (1:2:n) + n*10;
  Supp = [1, 0, 1, 0;
          leftx', ones(n, 1), zeros(n, 1), zeros(n, 1);
          leftz', zeros(6, 1), zeros(6, 1), ones(6, 1);
          rightz', zeros(6, 1), zeros(6, 1), ones(6, 1)];
  indp = (1:n)' + n*10;
  Load = [indp, -ones(n, 1), zeros(n, 1), zeros(n, 1)];
  control = 3*indp(1) - 2;
elseif strcmp(name, 'bistable')
  % MIURA POP-THROUGH: 5 x 5 cells at 30 deg, a vertex pushed through; springs stiffen
  % outside [45, 315] deg
  [Node, Panel, ~] = ConfigMiura(5, 5, 60, 2, 2, 30);
  MaxIcr = 160; blam = 0.06; Kf = 1e-1; Kb = Kf*10; C0 = 1e4; Abar = 1e-1;
  limits = [45, 315];
  n = 11; xz = (3:2:n)'; x = (2:2:n)'; rightz = [1; xz] + n*10;
  Supp = [1, 1, 1, 1;
          xz, 1 + 0*xz, 0*xz, 1 + 0*xz;
          rightz(1), 0, 1, 1;
          rightz(2:end), 0*rightz(2:end), 0*rightz(2:end), 1 + 0*rightz(2:end)];
  Load = [61, 0, 0, -1];
  control = 3*61;
else
  error('merlin_case: name must be bending, folding or bistable, got %s', name);
end
BarMater = @(Ex) Ogden(Ex, C0);
RotSpring = @(he, h0, kpi, L0) EnhancedLinear(he, h0, kpi, L0, limits(1), limits(2));
[truss, angles, F] = PrepareData(Node, Panel, Supp, Load, BarMater, RotSpring, Kf, Kb, Abar);
truss.U0 = zeros(3*size(truss.Node, 1), 1);
tic; t0 = cputime;
[U_his, LF_his] = PathAnalysis(truss, angles, F, blam, MaxIcr);
cpu = cputime - t0; wall = toc;
U_his = real(U_his); LF_his = real(LF_his);
nodes = truss.Node; bars = truss.Bars; area = truss.A; lengths = truss.L;
fixed = truss.FixedDofs; fold = angles.fold; bend = angles.bend;
kpf = angles.kpf; kpb = angles.kpb; pf0 = angles.pf0; pb0 = angles.pb0;
save('-v6', out, 'nodes', 'bars', 'area', 'lengths', 'fixed', 'fold', 'bend', 'kpf', ...
     'kpb', 'pf0', 'pb0', 'F', 'U_his', 'LF_his', 'C0', 'control', 'cpu', 'wall', 'blam', ...
     'limits');
end
