function read_export(file, first_rel_ns, last_rel_ns)
  % The dynamic record of an exported run, read by Octave alone: the samples whose receive
  % time lies in [first, last] (ns after the log's first sample), kept as the dynamic procedure
  % keeps them (both angles present, time increasing, the output advancing), their TE in the
  % gear's sense, and its mean and p2p in arcsec. Prints "key value" lines.
  s = load(file);
  ratio = s.results.gear.ratio;
  sgn = s.results.gear.direction_sign;
  t = s.receive_time_ns;
  rel = t - t(1);
  keep = rel >= int64(first_rel_ns) & rel <= int64(last_rel_ns) & ...
         ~isnan(s.theta_in) & ~isnan(s.theta_out);
  ti = s.theta_in(keep);
  to = s.theta_out(keep);
  tk = t(keep);
  direction = 1;
  if to(end) < to(1)
    direction = -1;
  end
  n = numel(ti);
  sel = false(n, 1);
  last_t = tk(1);
  last_o = 0;
  first = true;
  for i = 1:n
    if ~first && tk(i) <= last_t
      continue;
    end
    if ~first && ~((to(i) - last_o) * direction > 0)
      continue;
    end
    sel(i) = true;
    last_o = to(i);
    last_t = tk(i);
    first = false;
  end
  te = sgn * to(sel) - ti(sel) / ratio;
  turn = 2 * pi / ratio;
  te = te - turn * round(te / turn);
  arcsec = te * (180.0 * 3600.0 / pi);
  total = 0;
  for i = 1:numel(arcsec)
    total = total + arcsec(i);
  end
  printf('samples %d\n', numel(arcsec));
  printf('mean_arcsec %.17g\n', total / numel(arcsec));
  printf('p2p_arcsec %.17g\n', max(arcsec) - min(arcsec));
  printf('results_mean_arcsec %.17g\n', s.results.dynamic.mean_arcsec);
  printf('unit_theta_in %s\n', s.units.theta_in);
  printf('unit_torque %s\n', s.units.torque);
  printf('rows %d\n', numel(s.sync_counter));
  printf('class_sync_counter %s\n', class(s.sync_counter));
  printf('class_flags %s\n', class(s.flags));
  printf('results_json_chars %d\n', numel(s.results_json));
  printf('run_id %s\n', s.run_id);
end
